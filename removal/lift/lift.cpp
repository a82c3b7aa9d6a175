#include "removal/lift/lift.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/compute/memory.h"
#include "core/scene/gaussian_kernels.h"
#include "core/util/error.h"
#include "core/util/median.h"
#include "removal/masks/inpaint_mask.h"
#include "removal/selection/select_kdtree.h"

namespace goris {

namespace {

using kernels::logit_clamped;
constexpr int kAutoSamples = 512;

// The existing Gaussians as the lift reads them: centres in a k-d tree, in-plane sizes, shapes.
struct Neighbours {
  std::optional<PointKdTree> tree;
  std::vector<float> log_scale, rotation, in_plane;

  explicit Neighbours(const GaussianModel& model) {
    if (model.count() == 0) return;
    const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
    log_scale = model.tensor(Param::LogScale).value.to_host();
    rotation = model.tensor(Param::Rotation).value.to_host();
    std::vector<glm::vec3> pts(model.count());
    in_plane.resize(model.count());
    for (std::size_t i = 0; i < model.count(); ++i) {
      pts[i] = glm::vec3(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
      float s[3] = {std::exp(log_scale[i * 3]), std::exp(log_scale[i * 3 + 1]), std::exp(log_scale[i * 3 + 2])};
      std::sort(s, s + 3);
      in_plane[i] = 0.5f * (s[1] + s[2]);
    }
    tree.emplace(std::move(pts));
  }
  // Index and distance of the nearest existing Gaussian, or nullopt when there is none.
  std::optional<std::pair<std::uint32_t, float>> nearest(const glm::vec3& q) const {
    if (!tree) return std::nullopt;
    std::vector<Neighbor> nb;
    tree->knn(q, 1, nb);
    if (nb.empty()) return std::nullopt;
    return std::make_pair(nb[0].index, std::sqrt(nb[0].dist2));
  }
};

const float* pixel_of(const Image& img, std::size_t p) { return &img.pixels[p * std::size_t(img.channels)]; }

void check_map(const Image& map, const Camera& cam, int channels, const char* name, int view, bool required) {
  if (map.pixel_count() == 0) {
    if (required) throw Error("lift: reference view " + std::to_string(view) + " has no inpainted " + name + " map");
    return;
  }
  if (map.width != cam.width || map.height != cam.height || map.channels != channels)
    throw Error("lift: the inpainted " + std::string(name) + " map of reference view " + std::to_string(view) + " is " +
                std::to_string(map.width) + "x" + std::to_string(map.height) + "x" + std::to_string(map.channels) +
                ", expected " + std::to_string(cam.width) + "x" + std::to_string(cam.height) + "x" +
                std::to_string(channels));
}

// Rule of lift.h: k = clamp(round(median neighbour size / median pixel footprint), 1, max_stride).
int auto_stride(const Neighbours& nb, const LiftView& v, const std::vector<std::size_t>& masked, const LiftSettings& s) {
  if (!nb.tree || masked.empty()) return 1;
  const Camera& cam = v.camera;
  const float f = 0.5f * (cam.fx + cam.fy);
  std::vector<float> sizes, footprints;
  const std::size_t step = std::max<std::size_t>(1, masked.size() / kAutoSamples);
  for (std::size_t i = 0; i < masked.size(); i += step) {
    const std::size_t p = masked[i];
    const float z = v.maps->depth.pixels[p];
    if (!(z > 0) || !std::isfinite(z)) continue;
    const glm::vec3 X = back_project(cam, int(p % cam.width), int(p / cam.width), z);
    const auto n = nb.nearest(X);
    if (!n) continue;
    sizes.push_back(nb.in_plane[n->first]);
    footprints.push_back(z / f);
  }
  if (sizes.empty()) return 1;
  const float k = std::round(median_of(sizes) / median_of(footprints));
  return int(std::clamp(k, 1.0f, float(std::max(1, s.max_stride))));
}

}  // namespace

void append_gaussians(GaussianModel& model, const GaussianRows& rows) {
  const std::size_t n = model.count(), m = rows.count;
  for (int p = 0; p < kParamCount; ++p) {
    const std::vector<float>& src = p == int(Param::Position)       ? rows.position
                                    : p == int(Param::LogScale)     ? rows.log_scale
                                    : p == int(Param::Rotation)     ? rows.rotation
                                    : p == int(Param::OpacityLogit) ? rows.opacity_logit
                                    : p == int(Param::Sh)           ? rows.sh
                                                                    : rows.extra_logit;
    if (src.size() != m * std::size_t(param_width(Param(p))))
      throw Error(std::string("append_gaussians: ") + param_name(Param(p)) + " has " + std::to_string(src.size()) +
                  " values for " + std::to_string(m) + " Gaussians");
  }
  const bool filter3d = model.filter3d_var.size() == n && n > 0;
  if (filter3d && rows.filter3d_var.size() != m)
    throw Error("append_gaussians: the model has a 3D filter but the new rows carry " +
                std::to_string(rows.filter3d_var.size()) + " filter variances for " + std::to_string(m) + " Gaussians");
  if (m == 0) return;

  const Device dev = model.device();
  std::array<ParamTensor, kParamCount> old;
  for (int p = 0; p < kParamCount; ++p) old[p] = std::move(model.tensor(Param(p)));
  Buffer<float> old_filter = std::move(model.filter3d_var);
  model.allocate(n + m);  // zero gradients and moments everywhere
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = model.tensor(Param(p));
    const std::size_t w = std::size_t(t.width);
    const std::vector<float>& src = p == int(Param::Position)       ? rows.position
                                    : p == int(Param::LogScale)     ? rows.log_scale
                                    : p == int(Param::Rotation)     ? rows.rotation
                                    : p == int(Param::OpacityLogit) ? rows.opacity_logit
                                    : p == int(Param::Sh)           ? rows.sh
                                                                    : rows.extra_logit;
    device_copy(t.value.data(), dev, old[p].value.data(), dev, n * w * sizeof(float));
    device_copy(t.value.data() + n * w, dev, src.data(), Device::CPU, m * w * sizeof(float));
    device_copy(t.grad.data(), dev, old[p].grad.data(), dev, n * w * sizeof(float));
    device_copy(t.adam_m.data(), dev, old[p].adam_m.data(), dev, n * w * sizeof(float));
    device_copy(t.adam_v.data(), dev, old[p].adam_v.data(), dev, n * w * sizeof(float));
  }
  if (filter3d) {
    model.filter3d_var = Buffer<float>(n + m, dev);
    device_copy(model.filter3d_var.data(), dev, old_filter.data(), dev, n * sizeof(float));
    device_copy(model.filter3d_var.data() + n, dev, rows.filter3d_var.data(), Device::CPU, m * sizeof(float));
  }
}

LiftResult lift_reference_views(GaussianModel& model, const std::vector<LiftView>& views, const LiftSettings& s) {
  for (const LiftView& v : views) {
    if (!v.mask || !v.maps) throw Error("lift: reference view " + std::to_string(v.view_index) + " lacks its mask or maps");
    const Camera& cam = v.camera;
    if (cam.width <= 0 || cam.height <= 0 || !(cam.fx > 0) || !(cam.fy > 0))
      throw Error("lift: reference view " + std::to_string(v.view_index) + " has an invalid camera");
    if (v.mask->width != cam.width || v.mask->height != cam.height)
      throw Error("lift: the mask of reference view " + std::to_string(v.view_index) + " is " +
                  std::to_string(v.mask->width) + "x" + std::to_string(v.mask->height) + ", the camera " +
                  std::to_string(cam.width) + "x" + std::to_string(cam.height));
    check_map(v.maps->depth, cam, 1, "depth", v.view_index, true);
    check_map(v.maps->rgb, cam, 3, "rgb", v.view_index, true);
    check_map(v.maps->normal, cam, 3, "normal", v.view_index, false);
    check_map(v.maps->diffuse, cam, 3, "diffuse", v.view_index, false);
    check_map(v.maps->fresnel, cam, 3, "fresnel", v.view_index, false);
    check_map(v.maps->roughness, cam, 1, "roughness", v.view_index, false);
    check_map(v.maps->region, cam, 1, "region", v.view_index, false);
  }
  if (!(s.opacity > 0 && s.opacity < 1)) throw Error("lift: the opacity of new Gaussians must be in (0, 1)");

  const Neighbours nb(model);
  const bool filter3d = model.filter3d_var.size() == model.count() && model.count() > 0;
  LiftResult result;
  result.first_new = model.count();
  GaussianRows rows;
  ReferencePoints& ref = result.points;

  for (const LiftView& v : views) {
    const Camera& cam = v.camera;
    const MapSet& maps = *v.maps;
    const int W = cam.width;
    const float f = 0.5f * (cam.fx + cam.fy);
    const glm::mat3 Rt = glm::transpose(cam.R);
    std::vector<std::size_t> masked;
    for (std::size_t p = 0; p < v.mask->pixel_count(); ++p)
      if (v.mask->data[p]) masked.push_back(p);
    const int k = s.stride > 0 ? s.stride : auto_stride(nb, v, masked, s);
    result.stride.push_back(k);

    // The materials of a pixel: inpainted where there is a map, else the defaults.
    auto material = [&](std::size_t p, glm::vec3& diffuse, glm::vec3& fresnel, float& rough, float& region) {
      diffuse = maps.diffuse.pixel_count() ? glm::vec3(pixel_of(maps.diffuse, p)[0], pixel_of(maps.diffuse, p)[1],
                                                       pixel_of(maps.diffuse, p)[2])
                                           : glm::vec3(s.diffuse);
      fresnel = maps.fresnel.pixel_count() ? glm::vec3(pixel_of(maps.fresnel, p)[0], pixel_of(maps.fresnel, p)[1],
                                                       pixel_of(maps.fresnel, p)[2])
                                           : glm::vec3(s.fresnel);
      rough = maps.roughness.pixel_count() ? maps.roughness.pixels[p] : s.roughness;
      region = maps.region.pixel_count() ? maps.region.pixels[p] : s.region;
    };
    auto valid_depth = [&](std::size_t p) {
      const float z = maps.depth.pixels[p];
      return std::isfinite(z) && z > 0.0f;
    };

    // Reference points: every masked pixel with a depth.
    for (std::size_t p : masked) {
      if (!valid_depth(p)) continue;
      const int x = int(p % W), y = int(p / W);
      glm::vec3 diffuse, fresnel;
      float rough, region;
      material(p, diffuse, fresnel, rough, region);
      const float* c = pixel_of(maps.rgb, p);
      glm::vec3 n(0.0f);
      if (maps.normal.pixel_count()) {
        const float* nc = pixel_of(maps.normal, p);
        n = Rt * glm::vec3(nc[0], nc[1], nc[2]);
      }
      ref.position.push_back(back_project(cam, x, y, maps.depth.pixels[p]));
      ref.color.push_back(glm::vec3(c[0], c[1], c[2]));
      ref.normal.push_back(n);
      ref.diffuse.push_back(diffuse);
      ref.fresnel.push_back(fresnel);
      ref.roughness.push_back(rough);
      ref.region.push_back(region);
      ref.view.push_back(v.view_index);
      ref.pixel.push_back(glm::ivec2(x, y));
    }

    // New Gaussians: the stride grid, or the pixel nearest the centroid of a mask the grid misses.
    std::vector<std::size_t> samples;
    for (std::size_t p : masked) {
      const int x = int(p % W), y = int(p / W);
      if (x % k || y % k) continue;
      if (valid_depth(p)) samples.push_back(p);
      else ++result.skipped_no_depth;
    }
    if (samples.empty() && !masked.empty()) {
      glm::dvec2 c(0.0);
      for (std::size_t p : masked) c += glm::dvec2(double(p % W), double(p / W));
      c /= double(masked.size());
      double best = std::numeric_limits<double>::max();
      std::size_t pick = SIZE_MAX;
      for (std::size_t p : masked) {
        if (!valid_depth(p)) continue;
        const glm::dvec2 d = glm::dvec2(double(p % W), double(p / W)) - c;
        if (glm::dot(d, d) < best) best = glm::dot(d, d), pick = p;
      }
      if (pick != SIZE_MAX) samples.push_back(pick);
    }

    for (std::size_t p : samples) {
      const int x = int(p % W), y = int(p / W);
      const float z = maps.depth.pixels[p];
      const glm::vec3 X = back_project(cam, x, y, z);
      const float spacing = float(k) * z / f;
      rows.position.insert(rows.position.end(), {X.x, X.y, X.z});
      const auto near = nb.nearest(X);
      if (near && near->second <= s.neighbour_distance * spacing) {
        const std::size_t i = near->first;
        rows.log_scale.insert(rows.log_scale.end(), nb.log_scale.begin() + i * 3, nb.log_scale.begin() + i * 3 + 3);
        rows.rotation.insert(rows.rotation.end(), nb.rotation.begin() + i * 4, nb.rotation.begin() + i * 4 + 4);
        ++result.from_neighbour;
      } else {
        const float ls = std::log(spacing);
        rows.log_scale.insert(rows.log_scale.end(), {ls, ls, ls});
        rows.rotation.insert(rows.rotation.end(), {1.0f, 0.0f, 0.0f, 0.0f});
      }
      rows.opacity_logit.push_back(logit_clamped(s.opacity));
      const float* c = pixel_of(maps.rgb, p);
      const std::size_t sh0 = rows.sh.size();
      rows.sh.resize(sh0 + std::size_t(kMaxShCoeffs) * 3, 0.0f);
      for (int ch = 0; ch < 3; ++ch) rows.sh[sh0 + ch] = kernels::sh_dc_from_colour(c[ch]);
      glm::vec3 diffuse, fresnel;
      float rough, region;
      material(p, diffuse, fresnel, rough, region);
      float e[extra::kCount];
      for (int ch = 0; ch < 3; ++ch) {
        e[extra::kDiffuse + ch] = logit_clamped(diffuse[ch]);
        e[extra::kFresnel + ch] = logit_clamped(fresnel[ch]);
      }
      e[extra::kRoughness] = logit_clamped(rough);
      e[extra::kRegion] = logit_clamped(region);
      e[extra::kLabel] = logit_clamped(s.label);
      rows.extra_logit.insert(rows.extra_logit.end(), e, e + extra::kCount);
      if (filter3d) rows.filter3d_var.push_back(0.2f * (z / cam.fx) * (z / cam.fx));
      ++rows.count;
    }
  }
  append_gaussians(model, rows);
  result.added = rows.count;
  return result;
}

}  // namespace goris
