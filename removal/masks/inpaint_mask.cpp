#include "removal/masks/inpaint_mask.h"

#include <atomic>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/util/error.h"
#include "removal/masks/inpaint_mask_scene.h"
#include "removal/selection/select_view.h"
#include "render/raster/rasterizer.h"

namespace goris {

namespace {

// What the visibility test needs of one view, on the host.
struct ViewData {
  Camera cam;
  std::vector<float> depth;          // removed surface z, 0 = none
  std::vector<std::uint8_t> cover;   // target covers the pixel
};

// Alpha and expected depth (depth / alpha) of a render; depth 0 where alpha <= min_alpha.
void render_depth(const GaussianModel& model, const Camera& cam, const RasterSettings& rs, float min_alpha,
                  std::vector<float>& alpha, std::vector<float>& depth) {
  const std::size_t hw = std::size_t(cam.width) * cam.height;
  if (model.count() == 0) {
    alpha.assign(hw, 0.0f);
    depth.assign(hw, 0.0f);
    return;
  }
  const RasterOutput r = rasterize(plain_gaussian_view(model), cam, rs, model.device());
  alpha = r.gbuffer.alpha.to_host();
  depth = r.gbuffer.depth.to_host();
  for (std::size_t p = 0; p < hw; ++p) depth[p] = alpha[p] > min_alpha && depth[p] > 0 ? depth[p] / alpha[p] : 0.0f;
}

Image one_channel(const std::vector<float>& v, int w, int h) {
  Image img(w, h, 1, Device::CPU);
  img.pixels.upload(v.data(), v.size());
  return img;
}

// Rule 3's "X is visible in view j".
bool visible_in(const ViewData& v, const glm::vec3& X, float near_plane, float tol) {
  const glm::vec3 c = v.cam.to_camera(X);
  if (!(c.z > near_plane)) return false;
  const float u = v.cam.fx * c.x / c.z + v.cam.cx, w = v.cam.fy * c.y / c.z + v.cam.cy;
  if (!(u >= 0.0f && w >= 0.0f && u < float(v.cam.width) && w < float(v.cam.height))) return false;
  const std::size_t q = std::size_t(int(w)) * v.cam.width + std::size_t(int(u));
  if (v.cover[q]) return false;
  const float d = v.depth[q];
  return d > 0.0f && std::fabs(c.z - d) <= tol * c.z;
}

}  // namespace

glm::vec3 back_project(const Camera& cam, int x, int y, float z) {
  const glm::vec3 pc(z * (float(x) + 0.5f - cam.cx) / cam.fx, z * (float(y) + 0.5f - cam.cy) / cam.fy, z);
  return glm::transpose(cam.R) * (pc - cam.t);
}

std::vector<InpaintMaskView> compute_inpaint_masks(const GaussianModel& kept, const GaussianModel& target,
                                                   const std::vector<Camera>& cameras,
                                                   const InpaintMaskSettings& s,
                                                   const std::function<void(std::size_t, std::size_t)>& progress) {
  if (cameras.empty()) throw Error("inpainting mask: no cameras");
  if (kept.device() != target.device()) throw Error("inpainting mask: the kept and target models live on different devices");
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const Camera& c = cameras[i];
    if (c.width <= 0 || c.height <= 0 || !(c.fx > 0) || !(c.fy > 0))
      throw Error("inpainting mask: camera " + std::to_string(i) + " has no valid size or focal length");
  }
  const std::size_t V = cameras.size();
  std::vector<ViewData> views(V);
  std::vector<InpaintMaskView> out(V);
  std::vector<float> alpha, depth, t_alpha, t_depth;
  for (std::size_t i = 0; i < V; ++i) {
    const Camera& cam = cameras[i];
    const int W = cam.width, H = cam.height;
    const std::size_t hw = std::size_t(W) * H;
    render_depth(kept, cam, s.raster, s.surface_alpha, alpha, depth);
    render_depth(target, cam, s.raster, 1e-4f, t_alpha, t_depth);
    ViewData& v = views[i];
    v.cam = cam;
    v.depth = depth;
    v.cover.assign(hw, 0);
    out[i].covered = Mask(W, H);
    for (std::size_t p = 0; p < hw; ++p) {
      const bool in_front = depth[p] == 0.0f || (t_depth[p] > 0.0f && t_depth[p] < depth[p] * (1.0f + s.depth_tolerance));
      if (t_alpha[p] > s.target_alpha && in_front) {
        v.cover[p] = 1;
        out[i].covered.data[p] = 255;
      }
    }
    out[i].removed_depth = one_channel(depth, W, H);
    out[i].removed_alpha = one_channel(alpha, W, H);
    out[i].target_depth = one_channel(t_depth, W, H);
    if (progress) progress(i + 1, 2 * V);
  }

  const float near_plane = s.raster.near_plane;
  for (std::size_t i = 0; i < V; ++i) {
    const ViewData& vi = views[i];
    const int W = vi.cam.width, H = vi.cam.height;
    Mask raw(W, H);
    std::atomic<std::size_t> empty_behind{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
      std::size_t empty = 0;
      for (int y = rows.begin(); y != rows.end(); ++y)
        for (int x = 0; x < W; ++x) {
          const std::size_t p = std::size_t(y) * W + x;
          if (!vi.cover[p]) continue;
          const float z = vi.depth[p];
          if (z == 0.0f) {
            ++empty;
            if (s.empty_behind_is_hole) raw.data[p] = 255;
            continue;
          }
          const glm::vec3 X = back_project(vi.cam, x, y, z);
          bool seen = false;
          for (std::size_t j = 0; j < V && !seen; ++j)
            if (j != i) seen = visible_in(views[j], X, near_plane, s.depth_tolerance);
          if (!seen) raw.data[p] = 255;
        }
      empty_behind += empty;
    });
    InpaintMaskView& o = out[i];
    o.mask = mask_and(close_mask(open_mask(raw, s.open_radius), s.close_radius), o.covered);
    o.stats.covered = count_set(o.covered);
    o.stats.empty_behind = empty_behind.load();
    o.stats.raw = count_set(raw);
    o.stats.masked = count_set(o.mask);
    if (progress) progress(V + i + 1, 2 * V);
  }
  return out;
}

std::vector<InpaintMaskView> compute_inpaint_masks(const GaussianModel& model, const std::vector<std::uint8_t>& removed,
                                                   const std::vector<Camera>& cameras,
                                                   const InpaintMaskSettings& settings,
                                                   const std::function<void(std::size_t, std::size_t)>& progress) {
  if (removed.size() != model.count())
    throw Error("inpainting mask: the removal mask has " + std::to_string(removed.size()) + " entries for " +
                std::to_string(model.count()) + " Gaussians");
  std::size_t n_removed = 0;
  for (std::uint8_t r : removed) n_removed += r ? 1 : 0;
  if (n_removed == 0) throw Error("inpainting mask: no Gaussian is selected for removal");
  if (n_removed == model.count()) throw Error("inpainting mask: every Gaussian is selected for removal");
  const SplitScene split = split_removed(model, removed);
  return compute_inpaint_masks(split.kept, split.target, cameras, settings, progress);
}

}  // namespace goris
