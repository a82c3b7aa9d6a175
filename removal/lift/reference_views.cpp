#include "removal/lift/reference_views.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "core/util/median.h"
#include "render/raster/rasterizer.h"

namespace goris {

namespace {

float angle_deg(const glm::vec3& a, const glm::vec3& b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)) * 180.0f / 3.14159265358979f;
}

}  // namespace

ReferenceChoice choose_reference_views(const std::vector<std::size_t>& mask_pixels,
                                       const std::vector<glm::vec3>& camera_centers, const glm::vec3& hole_center,
                                       const ReferenceViewSettings& s) {
  if (mask_pixels.size() != camera_centers.size())
    throw Error("reference views: " + std::to_string(mask_pixels.size()) + " mask sizes for " +
                std::to_string(camera_centers.size()) + " cameras");
  if (s.count < 1) throw Error("reference views: the number of views must be at least 1");
  const std::size_t min_pixels = std::max<std::size_t>(s.min_pixels, 1);
  std::vector<int> order;
  for (std::size_t v = 0; v < mask_pixels.size(); ++v)
    if (mask_pixels[v] >= min_pixels) order.push_back(int(v));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return mask_pixels[a] > mask_pixels[b]; });

  std::vector<glm::vec3> dir(mask_pixels.size(), glm::vec3(0.0f));
  for (int v : order) {
    const glm::vec3 d = hole_center - camera_centers[v];
    const float len = glm::length(d);
    if (len > 0) dir[v] = d / len;
  }
  ReferenceChoice choice;
  std::vector<std::uint8_t> taken(mask_pixels.size(), 0);
  float theta = s.min_angle_deg;
  const std::size_t want = std::min(std::size_t(s.count), order.size());
  while (choice.views.size() < want) {
    for (int v : order) {
      if (choice.views.size() == want) break;
      if (taken[v]) continue;
      bool apart = true;
      for (int c : choice.views) apart = apart && angle_deg(dir[v], dir[c]) >= theta;
      if (theta <= 0.0f || apart) {
        taken[v] = 1;
        choice.views.push_back(v);
        choice.angle_threshold.push_back(theta);
      }
    }
    theta = theta * 0.5f < 1.0f ? 0.0f : theta * 0.5f;
  }
  return choice;
}

std::optional<glm::vec3> hole_centroid(const std::vector<InpaintMaskView>& masks, const std::vector<Camera>& cameras) {
  if (masks.size() != cameras.size())
    throw Error("hole centroid: " + std::to_string(masks.size()) + " masks for " + std::to_string(cameras.size()) + " cameras");
  std::vector<float> xs, ys, zs;
  for (std::size_t v = 0; v < masks.size(); ++v) {
    const InpaintMaskView& m = masks[v];
    const Camera& cam = cameras[v];
    for (int y = 0; y < m.mask.height; ++y)
      for (int x = 0; x < m.mask.width; ++x) {
        if (!m.mask(x, y)) continue;
        const std::size_t p = std::size_t(y) * m.mask.width + x;
        const float z = m.removed_depth.pixels[p] > 0 ? m.removed_depth.pixels[p] : m.target_depth.pixels[p];
        if (!(z > 0)) continue;
        const glm::vec3 X = back_project(cam, x, y, z);
        xs.push_back(X.x);
        ys.push_back(X.y);
        zs.push_back(X.z);
      }
  }
  if (xs.empty()) return std::nullopt;
  return glm::vec3(median_of(xs), median_of(ys), median_of(zs));
}

ReferenceChoice choose_reference_views(const std::vector<InpaintMaskView>& masks, const std::vector<Camera>& cameras,
                                       const ReferenceViewSettings& settings) {
  const std::optional<glm::vec3> centre = hole_centroid(masks, cameras);
  if (!centre) return {};
  std::vector<std::size_t> pixels;
  std::vector<glm::vec3> centers;
  for (std::size_t v = 0; v < masks.size(); ++v) {
    pixels.push_back(masks[v].stats.masked);
    centers.push_back(cameras[v].center());
  }
  return choose_reference_views(pixels, centers, *centre, settings);
}

MapSet render_removed_maps(GaussianModel& kept, const Camera& cam, const RasterSettings& settings, float min_alpha) {
  const int W = cam.width, H = cam.height;
  const std::size_t hw = std::size_t(W) * H;
  MapSet maps;
  maps.rgb = Image(W, H, 3);
  maps.depth = Image(W, H, 1);
  maps.normal = Image(W, H, 3);
  maps.diffuse = Image(W, H, 3);
  maps.fresnel = Image(W, H, 3);
  maps.roughness = Image(W, H, 1);
  maps.region = Image(W, H, 1);
  if (kept.count() == 0) {
    for (const MapSlot& s : map_slots()) (maps.*s.member).pixels.fill_zero();
    return maps;
  }
  const RasterOutput r = rasterize(kept.view(true), cam, settings, kept.device());
  const std::vector<float> color = r.gbuffer.color.to_host(), alpha = r.gbuffer.alpha.to_host(),
                           depth = r.gbuffer.depth.to_host(), normal = r.gbuffer.normal.to_host(),
                           extras = r.gbuffer.extras.to_host();
  const int K = r.gbuffer.n_extras;
  if (K != extra::kCount) throw Error("render_removed_maps: the rasterizer returned " + std::to_string(K) + " extra channels");
  // (map, first extra channel, channels) for the material maps.
  struct Material {
    Image* map;
    int first, channels;
  };
  const Material materials[] = {{&maps.diffuse, extra::kDiffuse, 3},
                                {&maps.fresnel, extra::kFresnel, 3},
                                {&maps.roughness, extra::kRoughness, 1},
                                {&maps.region, extra::kRegion, 1}};
  for (std::size_t p = 0; p < hw; ++p) {
    const float a = alpha[p];
    const bool surface = a > min_alpha;
    for (int c = 0; c < 3; ++c) maps.rgb.pixels[p * 3 + c] = color[c * hw + p];
    maps.depth.pixels[p] = surface && depth[p] > 0 ? depth[p] / a : 0.0f;
    const float n[3] = {normal[p], normal[hw + p], normal[2 * hw + p]};
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c) maps.normal.pixels[p * 3 + c] = surface && len > 0 ? n[c] / len : 0.0f;
    for (const Material& m : materials)
      for (int c = 0; c < m.channels; ++c)
        m.map->pixels[p * m.channels + c] = surface ? extras[std::size_t(m.first + c) * hw + p] / a : 0.0f;
  }
  return maps;
}

}  // namespace goris
