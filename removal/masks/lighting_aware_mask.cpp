#include "removal/masks/lighting_aware_mask.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/gaussian_kernels.h"
#include "core/scene/gaussians.h"

#include "core/util/error.h"

namespace goris {

Mask lighting_aware_mask(const std::vector<float>& e, int width, int height, const LightingMaskSettings& s) {
  if (width <= 0 || height <= 0 || e.size() != std::size_t(width) * std::size_t(height))
    throw Error("lighting-aware mask", "the reflected-label image holds " + std::to_string(e.size()) +
                                           " values for a " + std::to_string(width) + "x" + std::to_string(height) +
                                           " view");
  if (!(s.tau >= 0) || !std::isfinite(s.tau)) throw Error("lighting-aware mask", "tau must be finite and >= 0");
  Mask m(width, height);
  for (std::size_t p = 0; p < e.size(); ++p) {
    if (!std::isfinite(e[p])) throw Error("lighting-aware mask", "non-finite reflected label at pixel " + std::to_string(p));
    m.data[p] = e[p] > s.tau ? 255 : 0;
  }
  const int r = s.dilate >= 0 ? s.dilate : soft_edge_radius(width);
  return dilate_mask(m, r);
}

float glossy_fresnel_reference(const GaussianModel& model, const SelectionMask& target, float quantile) {
  const ParamTensor& ex = model.tensor(Param::ExtraLogit);
  if (ex.width != extra::kCount)
    throw Error("lighting-aware mask", "the model has no material channels (a radiance run): nothing reflects");
  if (target.size() != model.count())
    throw Error("lighting-aware mask", "the selection has " + std::to_string(target.size()) + " entries for " +
                                           std::to_string(model.count()) + " Gaussians");
  const std::vector<float> logits = ex.value.to_host(), opacity = model.tensor(Param::OpacityLogit).value.to_host();
  using kernels::sigmoid;
  std::vector<std::pair<float, float>> f0_weight;  // (mean F0, opacity) of the glossy non-target Gaussians
  double total = 0;
  for (std::size_t i = 0; i < model.count(); ++i) {
    const float* e = &logits[i * extra::kCount];
    if (target[i] || sigmoid(e[extra::kRegion]) >= 0.5f) continue;
    const float f0 = (sigmoid(e[extra::kFresnel]) + sigmoid(e[extra::kFresnel + 1]) + sigmoid(e[extra::kFresnel + 2])) / 3;
    const float w = sigmoid(opacity[i]);
    if (!std::isfinite(f0) || !std::isfinite(w) || w <= 0) continue;
    f0_weight.emplace_back(f0, w);
    total += w;
  }
  if (f0_weight.empty() || total <= 0) return 1.0f;
  std::sort(f0_weight.begin(), f0_weight.end());
  const double wanted = std::clamp(double(quantile), 0.0, 1.0) * total;
  double acc = 0;
  for (const auto& [f0, w] : f0_weight) {
    acc += w;
    if (acc >= wanted) return std::max(f0, 1e-3f);
  }
  return std::max(f0_weight.back().first, 1e-3f);
}

}  // namespace goris
