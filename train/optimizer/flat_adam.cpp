#include "train/optimizer/flat_adam.h"

#include <cmath>
#include <string>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/parallel_for.h"
#include "core/util/error.h"
#include "train/optimizer/adam_kernel.h"
#include "train/optimizer/train_cuda.h"

namespace goris {

void FlatAdam::reset() {
  m_.fill_zero();
  v_.fill_zero();
  steps_ = 0;
}

void FlatAdam::step(Buffer<float>& params, const Buffer<float>& grads, float lr, const char* what) {
  const std::size_t n = params.size();
  if (grads.size() != n || m_.size() != n || m_.device() != params.device() || grads.device() != params.device())
    throw Error(what, "optimiser moments hold " + std::to_string(m_.size()) + " values on " +
                          device_name(m_.device()) + ", the parameters " + std::to_string(n) + " on " +
                          device_name(params.device()) + " with " + std::to_string(grads.size()) + " gradients");
  ++steps_;
  kernels::AdamStep s;
  s.lr = lr;
  s.beta1 = beta1;
  s.beta2 = beta2;
  s.eps = eps;
  s.bias1 = float(1.0 - std::pow(double(beta1), steps_));
  s.bias2 = float(1.0 - std::pow(double(beta2), steps_));
  // The flat buffer as n rows of one column: one work item per parameter.
  s.width = 1;
  s.col_begin = 0;
  s.group_width = 1;
  float* p = params.data();
  const float* g = grads.data();
  float* m = m_.data();
  float* v = v_.data();
  if (params.device() == Device::CPU) {
    parallel_for(Device::CPU, n, [=](std::size_t i) { kernels::adam_group_row(p, m, v, g, s, i); }, 1024);
    return;
  }
  GORIS_CUDA_CALL(what, goris::detail::adam_step_cuda(p, m, v, g, s, n));
}

}  // namespace goris
