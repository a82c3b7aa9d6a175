#include "removal/selection/selection_click_region.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/selection/gaussian_pixel_weights.h"
#include "removal/selection/select_view.h"
#include "removal/selection/selection_masks.h"
#include "removal/selection/selection_view_masks.h"
#include "render/raster/rasterizer.h"

namespace goris {

namespace {

// The flood fill at one colour tolerance.
Mask flood(const Image& photo, const std::vector<float>& depth, int x0, int y0, const float ref[3], float tol,
           float depth_step, const std::vector<float>* barrier) {
  const int w = photo.width, h = photo.height;
  const float* px = photo.pixels.data();
  Mask m(w, h);
  auto colour_ok = [&](std::size_t p) {
    const float* c = px + 3 * p;
    const float dr = c[0] - ref[0], dg = c[1] - ref[1], db = c[2] - ref[2];
    return dr * dr + dg * dg + db * db <= tol * tol;
  };
  std::vector<std::size_t> stack{std::size_t(y0) * std::size_t(w) + std::size_t(x0)};
  m.data[stack.back()] = 255;
  while (!stack.empty()) {
    const std::size_t p = stack.back();
    stack.pop_back();
    const int x = int(p % std::size_t(w)), y = int(p / std::size_t(w));
    const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
      const std::size_t q = std::size_t(ny[k]) * std::size_t(w) + std::size_t(nx[k]);
      if (m.data[q] || depth[q] <= 0.0f) continue;
      if (barrier && (*barrier)[q] > 0.5f) continue;
      if (std::abs(depth[q] - depth[p]) > depth_step * std::min(depth[p], depth[q])) continue;
      if (!colour_ok(q)) continue;
      m.data[q] = 255;
      stack.push_back(q);
    }
  }
  return m;
}

}  // namespace

ClickRegion grow_click_region(const Image& photo, const std::vector<float>& depth, int x, int y,
                              const ClickRegionSettings& s, const std::vector<float>* barrier) {
  const int w = photo.width, h = photo.height;
  if (photo.channels != 3 || photo.pixels.device() != Device::CPU || depth.size() != photo.pixel_count())
    throw Error("click", "the photo (RGB on the CPU) and the depth of the clicked view differ in size");
  if (barrier && barrier->size() != photo.pixel_count())
    throw Error("click", "the glossy mask and the photo of the clicked view differ in size");
  if (x < 0 || y < 0 || x >= w || y >= h) throw Error("click", "pixel outside the view");
  if (s.colour_ladder.empty() || !(s.leak_ratio > 1.0f) || !(s.depth_step > 0.0f))
    throw Error("click", "bad click region settings");
  ClickRegion r;
  r.mask = Mask(w, h);
  if (depth[std::size_t(y) * std::size_t(w) + std::size_t(x)] <= 0.0f) return r;
  // The click's colour: the median of each channel over the 5x5 pixels around it (one pixel of a textured
  // or anti-aliased photo is a noisy sample of the surface).
  float ref[3];
  const float* px = photo.pixels.data();
  for (int c = 0; c < 3; ++c) {
    std::vector<float> v;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
        v.push_back(px[3 * (std::size_t(yy) * std::size_t(w) + std::size_t(xx)) + std::size_t(c)]);
      }
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    ref[c] = v[v.size() / 2];
  }
  const std::size_t max_area = std::size_t(s.max_area_fraction * float(photo.pixel_count()));
  std::vector<Mask> rungs;
  for (float tol : s.colour_ladder) {
    rungs.push_back(flood(photo, depth, x, y, ref, tol, s.depth_step, barrier));
    r.rung_areas.push_back(count_set(rungs.back()));
  }
  std::size_t pick = 0, prev_area = 0;
  for (std::size_t k = 0; k < rungs.size(); ++k) {
    const std::size_t area = r.rung_areas[k];
    // A leak is a jump both relative to the region and in absolute terms (a small textured region doubles
    // as the tolerance passes its texture's contrast without leaving the object).
    const bool leak = area > max_area || (prev_area > 0 && float(area) > s.leak_ratio * float(prev_area) &&
                                          float(area - prev_area) > s.leak_area_fraction * float(photo.pixel_count()));
    if (leak) {
      if (k == 0) r.leaked_at_first = true;
      break;
    }
    pick = k;
    prev_area = area;
  }
  r.mask = std::move(rungs[pick]);
  r.tolerance = s.colour_ladder[pick];
  r.area = r.rung_areas[pick];
  return r;
}

std::vector<float> render_median_depth(const GaussianModel& model, const Camera& camera, const RasterSettings& raster) {
  return rasterize(plain_gaussian_view(model), camera, raster, model.device()).gbuffer.median_depth.to_host();
}

SelectionMask select_from_click_regions(const GaussianModel& model, const std::vector<ClickView>& views,
                                        const RasterSettings& raster, const WeightVoteSettings& s) {
  const std::size_t n = model.count();
  std::vector<std::uint8_t> seen(n, 0), outside_once(n, 0);
  for (const ClickView& v : views) {
    const PixelWeights w = gaussian_pixel_weights(model, {v.camera}, {v.region}, raster);
    for (std::size_t k = 0; k < n; ++k) {
      const float total = w.inside[k] + w.outside[k];
      if (!(total >= s.min_weight)) continue;
      seen[k] = 1;
      if (w.inside[k] < s.min_inside_share * total) outside_once[k] = 1;
    }
  }
  SelectionMask sel(n, 0);
  for (std::size_t k = 0; k < n; ++k) sel[k] = seen[k] && !outside_once[k];
  return sel;
}

SelectionMask revote_with_view_masks(const GaussianModel& model, const SelectionMask& selection,
                                     const std::vector<View>& views, const RasterSettings& raster,
                                     const std::vector<const std::vector<float>*>& glossy) {
  std::vector<MaskedView> masked;
  for (std::size_t k = 0; k < views.size(); ++k) {
    Mask m = selection_silhouette_mask(model, selection, views[k].camera, raster);
    const std::vector<float>* g = k < glossy.size() ? glossy[k] : nullptr;
    if (g && g->size() != m.data.size())
      throw Error("selection", "the glossy mask of view " + views[k].name + " has " + std::to_string(g->size()) +
                                   " pixels, its camera " + std::to_string(m.data.size()));
    if (g)
      for (std::size_t p = 0; p < m.data.size(); ++p)
        if ((*g)[p] > 0.5f) m.data[p] = 0;
    MaskedView mv;
    mv.name = views[k].name;
    mv.camera = views[k].camera;
    mv.mask = mask_to_image(m);
    masked.push_back(std::move(mv));
  }
  return labels_from_masks(model, masked, {}, raster).selected;
}

}  // namespace goris
