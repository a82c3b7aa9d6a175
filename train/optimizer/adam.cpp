#include "train/optimizer/adam.h"

#include <algorithm>
#include <cmath>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/parallel_for.h"
#include "core/util/error.h"
#include "train/optimizer/adam_kernel.h"
#include "train/optimizer/train_cuda.h"
#include "train/optimizer/train_kernels.h"

namespace goris {

void GaussianAdam::step(GaussianModel& model, ParamGroup group, float lr, int col_end) {
  GroupSpan span = group_span(group);
  if (col_end > 0) span.col_end = std::min(span.col_end, col_end);
  ParamTensor& t = model.tensor(span.param);
  const int t_step = ++steps[int(group)];
  kernels::AdamStep s;
  s.lr = lr;
  s.beta1 = beta1;
  s.beta2 = beta2;
  s.eps = eps;
  s.bias1 = float(1.0 - std::pow(double(beta1), t_step));
  s.bias2 = float(1.0 - std::pow(double(beta2), t_step));
  s.width = t.width;
  s.col_begin = span.col_begin;
  s.group_width = span.col_end - span.col_begin;
  const size_t n = span.col_end > span.col_begin ? model.count() : 0;
  float* p = t.value.data();
  float* m = t.adam_m.data();
  float* v = t.adam_v.data();
  const float* g = t.grad.data();
  if (model.device() == Device::CPU)
    parallel_for(Device::CPU, n, [=](size_t r) { kernels::adam_group_row(p, m, v, g, s, r); }, 2048);
  else
    GORIS_CUDA_CALL("optimiser", detail::adam_step_cuda(p, m, v, g, s, n));
}

void reset_moments(GaussianModel& model, ParamGroup group) {
  const GroupSpan span = group_span(group);
  ParamTensor& t = model.tensor(span.param);
  for (Buffer<float>* b : {&t.adam_m, &t.adam_v}) {
    float* d = b->data();
    const int w = t.width, c0 = span.col_begin, c1 = span.col_end;
    if (model.device() == Device::CPU)
      parallel_for(Device::CPU, model.count(), [=](size_t r) { kernels::zero_columns(d, w, c0, c1, r); });
    else
      GORIS_CUDA_CALL("optimiser", detail::zero_columns_cuda(d, w, c0, c1, model.count()));
  }
}

}  // namespace goris
