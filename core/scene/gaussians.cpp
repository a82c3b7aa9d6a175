#include "core/scene/gaussians.h"

#include <cmath>
#include <vector>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/parallel_for.h"
#include "core/scene/gaussian_kernels.h"
#include "core/scene/gaussians_cuda.h"
#include "core/util/error.h"

namespace goris {

namespace extra {
const std::array<const char*, kCount> kPlyNames = {"diffuse_0", "diffuse_1", "diffuse_2", "fresnel_0", "fresnel_1",
                                                   "fresnel_2", "roughness", "region",    "label"};
}

namespace {
constexpr const char* kParamNames[kParamCount] = {"position", "log_scale", "rotation", "opacity", "sh", "extras"};
constexpr int kParamWidths[kParamCount] = {3, 3, 4, 1, kMaxShCoeffs * 3, extra::kCount};
constexpr const char* kWho = "scene model";
}  // namespace

const char* param_name(Param p) { return kParamNames[int(p)]; }
int param_width(Param p) { return kParamWidths[int(p)]; }

void GaussianModel::allocate(size_t n) {
  count_ = n;
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = tensors_[p];
    t.width = kParamWidths[p];
    const size_t len = n * size_t(t.width);
    t.value = Buffer<float>(len, device_);
    t.grad = Buffer<float>(len, device_);
    t.adam_m = Buffer<float>(len, device_);
    t.adam_v = Buffer<float>(len, device_);
    t.grad.fill_zero();
    t.adam_m.fill_zero();
    t.adam_v.fill_zero();
  }
  filter3d_var = Buffer<float>();
  extras_activated_ = Buffer<float>();
  extras_activated_grad_ = Buffer<float>();
}

GaussianModel GaussianModel::copy_to(Device d) const {
  GaussianModel m(d);
  m.count_ = count_;
  m.sh_degree = sh_degree;
  m.max_sh_degree = max_sh_degree;
  for (int p = 0; p < kParamCount; ++p) {
    const ParamTensor& t = tensors_[p];
    ParamTensor& o = m.tensors_[p];
    o.width = t.width;
    o.value = t.value.copy_to(d);
    o.grad = t.grad.copy_to(d);
    o.adam_m = t.adam_m.copy_to(d);
    o.adam_v = t.adam_v.copy_to(d);
  }
  m.filter3d_var = filter3d_var.copy_to(d);
  return m;
}

GaussianView GaussianModel::view(bool with_extras) {
  GaussianView v;
  v.count = int(count_);
  v.positions = values(Param::Position);
  v.log_scales = values(Param::LogScale);
  v.rotations = values(Param::Rotation);
  v.opacity_logits = values(Param::OpacityLogit);
  v.sh = values(Param::Sh);
  v.sh_degree = sh_degree;
  v.filter3d_var = filter3d_var.size() == count_ && count_ > 0 ? filter3d_var.data() : nullptr;
  if (with_extras) {
    const size_t n = count_ * extra::kCount;
    if (extras_activated_.size() != n) extras_activated_ = Buffer<float>(n, device_);
    const float* logits = values(Param::ExtraLogit);
    float* act = extras_activated_.data();
    if (device_ == Device::CPU)
      parallel_for(Device::CPU, n, [=](size_t i) { kernels::extras_forward(logits, act, i); });
    else
      GORIS_CUDA_CALL(kWho, detail::extras_forward_cuda(logits, act, n));
    v.extras = act;
    v.n_extras = extra::kCount;
  }
  return v;
}

void GaussianModel::derive_diffuse_from_sh() {
  const float* sh = values(Param::Sh);
  float* logits = values(Param::ExtraLogit);
  const int sw = param_width(Param::Sh), ew = extra::kCount, first = extra::kDiffuse;
  if (device_ == Device::CPU)
    parallel_for(Device::CPU, count_, [=](size_t i) { kernels::diffuse_from_sh_dc(sh, sw, logits, ew, first, i); });
  else
    GORIS_CUDA_CALL(kWho, detail::diffuse_from_sh_dc_cuda(sh, sw, logits, ew, first, count_));
}

GaussianGradView GaussianModel::grad_view(bool with_extras) {
  GaussianGradView g;
  g.positions = grads(Param::Position);
  g.log_scales = grads(Param::LogScale);
  g.rotations = grads(Param::Rotation);
  g.opacity_logits = grads(Param::OpacityLogit);
  g.sh = grads(Param::Sh);
  if (with_extras) {
    const size_t n = count_ * extra::kCount;
    if (extras_activated_grad_.size() != n) {
      extras_activated_grad_ = Buffer<float>(n, device_);
      extras_activated_grad_.fill_zero();
    }
    g.extras = extras_activated_grad_.data();
  }
  return g;
}

void GaussianModel::backprop_extras() {
  const size_t n = count_ * extra::kCount;
  if (extras_activated_grad_.size() != n || extras_activated_.size() != n)
    throw Error("GaussianModel::backprop_extras: called without view(true) and grad_view(true) for this model size");
  const float* act = extras_activated_.data();
  float* act_grad = extras_activated_grad_.data();
  float* logit_grad = grads(Param::ExtraLogit);
  if (device_ == Device::CPU)
    parallel_for(Device::CPU, n, [=](size_t i) { kernels::extras_backward(act, act_grad, logit_grad, i); });
  else
    GORIS_CUDA_CALL(kWho, detail::extras_backward_cuda(act, act_grad, logit_grad, n));
}

void GaussianModel::zero_grad() {
  for (auto& t : tensors_) t.grad.fill_zero();
  if (!extras_activated_grad_.empty()) extras_activated_grad_.fill_zero();
}

}  // namespace goris
