#include "removal/masks/lighting_aware_mask.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
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

namespace {

// The model's material channels, checked: present, and a mask of one entry per Gaussian.
const ParamTensor& material_channels(const GaussianModel& model, std::size_t mask_size) {
  const ParamTensor& ex = model.tensor(Param::ExtraLogit);
  if (ex.width != extra::kCount)
    throw Error("lighting-aware mask", "the model has no material channels (a radiance run): nothing reflects");
  if (mask_size != model.count())
    throw Error("lighting-aware mask", "the selection has " + std::to_string(mask_size) + " entries for " +
                                           std::to_string(model.count()) + " Gaussians");
  return ex;
}

}  // namespace

std::optional<float> fresnel_quantile(const GaussianModel& model, const SelectionMask& among, float quantile) {
  const ParamTensor& ex = material_channels(model, among.size());
  const std::vector<float> logits = ex.value.to_host(), opacity = model.tensor(Param::OpacityLogit).value.to_host();
  using kernels::sigmoid;
  std::vector<std::pair<float, float>> f0_weight;  // (mean F0, opacity)
  double total = 0;
  for (std::size_t i = 0; i < model.count(); ++i) {
    if (!among[i]) continue;
    const float* e = &logits[i * extra::kCount];
    const float f0 = (sigmoid(e[extra::kFresnel]) + sigmoid(e[extra::kFresnel + 1]) + sigmoid(e[extra::kFresnel + 2])) / 3;
    const float w = sigmoid(opacity[i]);
    if (!std::isfinite(f0) || !std::isfinite(w) || w <= 0) continue;
    f0_weight.emplace_back(f0, w);
    total += w;
  }
  if (f0_weight.empty() || total <= 0) return std::nullopt;
  std::sort(f0_weight.begin(), f0_weight.end());
  const double wanted = std::clamp(double(quantile), 0.0, 1.0) * total;
  double acc = 0;
  for (const auto& [f0, w] : f0_weight) {
    acc += w;
    if (acc >= wanted) return f0;
  }
  return f0_weight.back().first;
}

float glossy_fresnel_reference(const GaussianModel& model, const SelectionMask& target, float quantile) {
  const ParamTensor& ex = material_channels(model, target.size());
  const std::vector<float> logits = ex.value.to_host();
  SelectionMask glossy(model.count(), 0);  // the glossy non-target Gaussians
  for (std::size_t i = 0; i < model.count(); ++i)
    glossy[i] = !target[i] && kernels::sigmoid(logits[i * extra::kCount + extra::kRegion]) < 0.5f;
  const std::optional<float> f0 = fresnel_quantile(model, glossy, quantile);
  return f0 ? std::max(*f0, 1e-3f) : 1.0f;
}

}  // namespace goris
