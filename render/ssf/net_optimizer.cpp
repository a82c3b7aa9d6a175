#include "render/ssf/net_optimizer.h"

#include <cmath>
#include <string>

#include "core/compute/parallel_for.h"
#include "core/train/adam_kernel.h"
#include "core/util/error.h"
#ifdef GORIS_WITH_CUDA
#include "core/train/train_cuda.h"
#endif

namespace goris::ssf {

NetAdam::NetAdam(const RoughnessNet<float>& net)
    : m_(net.param_count(), net.device()), v_(net.param_count(), net.device()) {
  reset();
}

void NetAdam::reset() {
  m_.fill_zero();
  v_.fill_zero();
  steps_ = 0;
}

void NetAdam::step(RoughnessNet<float>& net, float lr) {
  const std::size_t n = net.param_count();
  if (m_.size() != n || m_.device() != net.device())
    throw Error("roughness net optimiser", "moments hold " + std::to_string(m_.size()) + " values on " +
                                               device_name(m_.device()) + ", the net has " + std::to_string(n) +
                                               " on " + device_name(net.device()));
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
  float* p = net.params().data();
  const float* g = net.grads().data();
  float* m = m_.data();
  float* v = v_.data();
  if (net.device() == Device::CPU) {
    parallel_for(Device::CPU, n, [=](std::size_t i) { kernels::adam_group_row(p, m, v, g, s, i); }, 1024);
    return;
  }
#ifdef GORIS_WITH_CUDA
  goris::detail::adam_step_cuda(p, m, v, g, s, n);
#else
  throw Error("roughness net optimiser", "CUDA net in a build without the CUDA backend");
#endif
}

}  // namespace goris::ssf
