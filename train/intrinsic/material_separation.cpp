#include "train/intrinsic/material_separation.h"

#include <algorithm>
#include <string>

#include "core/util/error.h"
#include "core/util/median.h"
#include "render/raster/rasterizer.h"

namespace goris {

namespace {

struct Samples {
  std::vector<float> roughness, f0, region;
};

double mean_of(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += double(x);
  return s / double(v.size());
}

MaterialStats stats_of(const Samples& s) {
  MaterialStats m;
  m.pixels = s.roughness.size();
  m.roughness_median = median_of(s.roughness);
  m.roughness_mean = mean_of(s.roughness);
  m.f0_median = median_of(s.f0);
  m.f0_mean = mean_of(s.f0);
  m.region_median = median_of(s.region);
  m.region_mean = mean_of(s.region);
  return m;
}

}  // namespace

double probability_greater(std::vector<float> rest, std::vector<float> glossy) {
  if (rest.empty() || glossy.empty()) throw Error("material separation", "an empty sample has no AUC");
  std::sort(rest.begin(), rest.end());
  std::sort(glossy.begin(), glossy.end());
  // For each rest value: how many glossy values lie below it, and how many equal it.
  double wins = 0;
  for (float r : rest) {
    const auto lo = std::lower_bound(glossy.begin(), glossy.end(), r);
    const auto hi = std::upper_bound(lo, glossy.end(), r);
    wins += double(lo - glossy.begin()) + 0.5 * double(hi - lo);
  }
  return wins / (double(rest.size()) * double(glossy.size()));
}

MaterialSeparation measure_material_separation(const GaussianView& gaussians, const std::vector<TrainView>& views,
                                               const RasterSettings& raster, Device device) {
  if (gaussians.n_extras != extra::kCount)
    throw Error("material separation", "the model has no material channels (a radiance run?)");
  MaterialSeparation out;
  Samples glossy, rest;
  for (const TrainView& v : views) {
    const std::size_t hw = std::size_t(v.camera.width) * std::size_t(v.camera.height);
    if (v.glossy_mask.size() != hw) continue;
    const RasterOutput r = rasterize(gaussians, v.camera, raster, device);
    const std::vector<float> alpha = r.gbuffer.alpha.to_host(), extras = r.gbuffer.extras.to_host();
    auto channel = [&](int c, std::size_t p) { return extras[std::size_t(c) * hw + p]; };
    ++out.views;
    for (std::size_t p = 0; p < hw; ++p) {
      if (alpha[p] < 0.5f) continue;
      const float inv = 1.0f / alpha[p];  // the blend of the Gaussians' values, not of values and background
      Samples& side = v.glossy_mask[p] >= 0.5f ? glossy : rest;
      side.roughness.push_back(channel(extra::kRoughness, p) * inv);
      side.f0.push_back((channel(extra::kFresnel, p) + channel(extra::kFresnel + 1, p) + channel(extra::kFresnel + 2, p)) *
                        inv / 3.0f);
      side.region.push_back(channel(extra::kRegion, p) * inv);
    }
  }
  if (glossy.roughness.empty() || rest.roughness.empty())
    throw Error("material separation", "no opaque " + std::string(glossy.roughness.empty() ? "glossy" : "non-glossy") +
                                           " pixel in " + std::to_string(views.size()) + " views with glossy masks");
  out.glossy = stats_of(glossy);
  out.rest = stats_of(rest);
  out.roughness_auc = probability_greater(std::move(rest.roughness), std::move(glossy.roughness));
  return out;
}

}  // namespace goris
