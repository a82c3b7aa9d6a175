#include "removal/masks/inpaint_mask_scene.h"

#include <string>

#include "core/util/error.h"

namespace goris {

namespace {

// Rows i of a [N][width] buffer with take[i] set (== want), as a new buffer on the same device.
Buffer<float> take_rows(const Buffer<float>& src, int width, const std::vector<std::uint8_t>& take, bool want,
                        std::size_t kept) {
  const std::vector<float> host = src.to_host();
  std::vector<float> out;
  out.reserve(kept * std::size_t(width));
  for (std::size_t i = 0; i < take.size(); ++i)
    if ((take[i] != 0) == want) out.insert(out.end(), host.begin() + i * width, host.begin() + (i + 1) * width);
  return Buffer<float>(out, src.device());
}

GaussianModel select_rows(const GaussianModel& model, const std::vector<std::uint8_t>& take, bool want) {
  if (take.size() != model.count())
    throw Error("selecting Gaussians: the mask has " + std::to_string(take.size()) + " entries for " +
                std::to_string(model.count()) + " Gaussians");
  std::size_t k = 0;
  for (std::uint8_t t : take) k += (t != 0) == want ? 1 : 0;
  GaussianModel m(model.device());
  m.allocate(k);
  m.sh_degree = model.sh_degree;
  m.max_sh_degree = model.max_sh_degree;
  for (int p = 0; p < kParamCount; ++p) {
    const ParamTensor& s = model.tensor(Param(p));
    ParamTensor& d = m.tensor(Param(p));
    d.value = take_rows(s.value, s.width, take, want, k);
    d.grad = take_rows(s.grad, s.width, take, want, k);
    d.adam_m = take_rows(s.adam_m, s.width, take, want, k);
    d.adam_v = take_rows(s.adam_v, s.width, take, want, k);
  }
  if (model.filter3d_var.size() == model.count() && model.count() > 0)
    m.filter3d_var = take_rows(model.filter3d_var, 1, take, want, k);
  return m;
}

}  // namespace

GaussianModel subset_model(const GaussianModel& model, const std::vector<std::uint8_t>& take) {
  return select_rows(model, take, true);
}

SplitScene split_removed(const GaussianModel& model, const std::vector<std::uint8_t>& removed) {
  return {select_rows(model, removed, false), select_rows(model, removed, true)};
}

}  // namespace goris
