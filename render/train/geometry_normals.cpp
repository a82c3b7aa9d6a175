#include "render/train/geometry_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "core/io/image.h"
#include "core/train/depth_normal_loss.h"
#include "core/train/glossy_plane.h"
#include "core/train/normal_prior.h"
#include "core/train/run_folder.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/train/raster_renderer.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

constexpr int kSmoothRadius = 2;           // the 5 x 5 window of the depth normals' edge-stopping average
constexpr float kSmoothDepth = 0.02f;      // relative depth difference of the pixels averaged together
constexpr double kPlaneBand = 3.0;         // x the plane's inlier tolerance: "on the plane"

// Camera-space point of pixel (x, y) at camera depth z.
glm::vec3 camera_point(const Camera& c, int x, int y, float z) {
  return {(float(x) + 0.5f - c.cx) / c.fx * z, (float(y) + 0.5f - c.cy) / c.fy * z, z};
}

// The depth normals of a view averaged over the window's pixels of similar depth; zero where uncovered.
std::vector<float> smoothed_depth_normals(const Camera& c, const std::vector<float>& depth,
                                          const std::vector<float>& alpha) {
  const int w = c.width, h = c.height;
  const std::size_t hw = std::size_t(w) * h;
  std::vector<float> raw(3 * hw, 0.0f), out(3 * hw, 0.0f);
  normal_from_depth<float>(depth.data(), w, h, c.fx, c.fy, c.cx, c.cy, raw.data());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * w + x;
      const float z = depth[p];
      if (!(alpha[p] > 0.5f) || !(z > 0)) continue;
      glm::vec3 sum(0.0f);
      for (int dy = -kSmoothRadius; dy <= kSmoothRadius; ++dy)
        for (int dx = -kSmoothRadius; dx <= kSmoothRadius; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const std::size_t q = std::size_t(qy) * w + qx;
          if (!(alpha[q] > 0.5f) || !(std::abs(depth[q] - z) <= kSmoothDepth * z)) continue;
          sum += glm::vec3(raw[q], raw[hw + q], raw[2 * hw + q]);  // zero where degenerate
        }
      const float len = glm::length(sum);
      if (!(len > 1e-6f)) continue;
      for (int k = 0; k < 3; ++k) out[k * hw + p] = sum[k] / len;
    }
  return out;
}

}  // namespace

GeometryNormals geometry_normal_priors(const GaussianModel& model, const std::vector<TrainView>& views,
                                       const RasterSettings& raster, Device device) {
  GeometryNormals out;
  // The glossy plane, as the glossy plane constraint finds it (needs the views' glossy masks).
  MirrorPlane plane;
  PlaneFootprint footprint;
  const bool any_gloss = std::any_of(views.begin(), views.end(), [](const TrainView& v) { return !v.glossy_mask.empty(); });
  if (any_gloss) {
    const std::vector<std::uint8_t> over = over_glossy_pixels(model, views);
    plane = glossy_surface_plane(model, views, over);
    if (plane.found) footprint = PlaneFootprint(model.tensor(Param::Position).value.to_host(), plane, over);
  }
  out.plane = plane.found;

  GaussianModel& m = const_cast<GaussianModel&>(model);  // view() hands out pointers; nothing is written
  const GaussianView g = m.view(false);
  for (const TrainView& v : views) {
    const Camera& c = v.camera;
    const RasterOutput r = rasterize(g, c, raster, device);
    const std::vector<float> depth = r.gbuffer.median_depth.to_host(), alpha = r.gbuffer.alpha.to_host();
    std::vector<float> prior = smoothed_depth_normals(c, depth, alpha);
    const std::size_t hw = std::size_t(c.width) * c.height;
    const glm::dmat3 to_world = glm::transpose(glm::dmat3(c.R));
    const glm::dvec3 eye = glm::dvec3(c.center());
    // The plane's normal in camera space, turned to face this camera.
    glm::dvec3 n_cam = glm::dmat3(c.R) * plane.normal;
    if (plane.signed_distance(eye) < 0) n_cam = -n_cam;
    for (std::size_t p = 0; p < hw; ++p) {
      if (!(alpha[p] > 0.5f) || !(depth[p] > 0)) continue;
      ++out.covered;
      const bool glossy = !v.glossy_mask.empty() && v.glossy_mask[p] > 0.5f;
      if (plane.found && glossy) {
        const int x = int(p % std::size_t(c.width)), y = int(p / std::size_t(c.width));
        const glm::dvec3 cam_p = glm::dvec3(camera_point(c, x, y, depth[p]));
        const glm::dvec3 world_p = to_world * (cam_p - glm::dvec3(c.t));
        const glm::dvec3 dir = world_p - eye;
        const double d_eye = plane.signed_distance(eye), d_p = plane.signed_distance(world_p);
        // On the plane, or beyond it as seen from this camera; and the ray meets the plane inside its footprint.
        const bool beyond = d_eye * d_p < 0;
        const double denom = glm::dot(plane.normal, dir);
        if ((std::abs(d_p) <= kPlaneBand * plane.tolerance || beyond) && std::abs(denom) > 1e-12) {
          const double s = -d_eye / denom;  // eye + s * dir lies on the plane
          if (s > 0 && footprint.contains(eye + s * dir)) {
            for (int k = 0; k < 3; ++k) prior[k * hw + p] = float(n_cam[k]);
            ++out.plane_pixels;
            out.beyond_pixels += beyond && std::abs(d_p) > kPlaneBand * plane.tolerance;
            continue;
          }
        }
      }
      out.depth_pixels += prior[p] != 0.0f || prior[hw + p] != 0.0f || prior[2 * hw + p] != 0.0f;
    }
    out.priors.push_back(std::move(prior));
  }
  return out;
}

void save_normal_prior_folder(const fs::path& dir, const std::vector<TrainView>& views,
                              const std::vector<std::vector<float>>& priors) {
  if (priors.size() != views.size())
    throw Error(dir.string(), std::to_string(priors.size()) + " normal priors for " + std::to_string(views.size()) + " views");
  fs::create_directories(dir);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Camera& c = views[i].camera;
    const std::size_t hw = std::size_t(c.width) * c.height;
    const glm::mat3 to_world = glm::transpose(c.R);
    std::vector<float> px(3 * hw, 0.5f);
    for (std::size_t p = 0; p < hw; ++p) {
      const glm::vec3 n(priors[i][p], priors[i][hw + p], priors[i][2 * hw + p]);
      if (glm::length(n) < 0.5f) continue;  // no prior: encodes the zero vector
      const glm::vec3 nw = to_world * n;
      for (int k = 0; k < 3; ++k) px[3 * p + k] = nw[k] * 0.5f + 0.5f;
    }
    Image img;
    img.width = c.width, img.height = c.height, img.channels = 3;
    img.pixels = Buffer<float>(px, Device::CPU);
    save_png(dir / ("normal_" + views[i].name + ".png"), img, /*sixteen_bit=*/true);
  }
}

std::optional<std::string> apply_geometry_normals(Trainer& trainer, const fs::path& run_dir) {
  const TrainConfig& config = trainer.config();
  if (!trainer.intrinsic() || !config.intrinsic.geometry_normals || !config.intrinsic.normals.empty() ||
      trainer.state().iteration < config.shading_from())
    return std::nullopt;
  if (run_dir.empty()) throw Error("intrinsic_geometry_normals: the normal prior needs a run folder for its maps");
  const GeometryNormals g = geometry_normal_priors(trainer.model(), trainer.views(),
                                                   RasterRenderer::settings_for(config), trainer.device());
  const fs::path dir = run_dir / "geometry_normals";
  save_normal_prior_folder(dir, trainer.views(), g.priors);
  TrainConfig next = config;
  next.intrinsic.normals = dir.string();
  trainer.switch_mode(next, trainer.renderer(), [&](std::vector<TrainView>& views) { load_normal_priors(dir, views); });
  write_run_config(run_dir, trainer.config());
  const double cov = double(std::max<std::size_t>(g.covered, 1));
  char line[256];
  std::snprintf(line, sizeof line,
                "normal prior from the geometry at iteration %d: %s%.1f %% of the covered pixels on the glossy plane, "
                "%.1f %% from the depth; maps in %s",
                trainer.state().iteration, g.plane ? "" : "no glossy plane, ", 100.0 * double(g.plane_pixels) / cov,
                100.0 * double(g.depth_pixels) / cov, dir.string().c_str());
  return std::string(line);
}

}  // namespace goris
