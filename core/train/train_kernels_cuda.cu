// CUDA twin of the training loop's per-element kernels (maths in adam_kernel.h and train_kernels.h).
#include "core/compute/buffer.h"
#include "core/compute/parallel_for.h"
#include "core/train/adam_kernel.h"
#include "core/train/train_cuda.h"
#include "core/train/train_kernels.h"

namespace goris::detail {

void adam_step_cuda(float* p, float* m, float* v, const float* g, const kernels::AdamStep& s, size_t n) {
  const kernels::AdamStep step = s;
  parallel_for(Device::CUDA, n, [=] __device__(size_t i) { kernels::adam_group_row(p, m, v, g, step, i); });
}

void zero_columns_cuda(float* data, int width, int col_begin, int col_end, size_t rows) {
  parallel_for(Device::CUDA, rows,
               [=] __device__(size_t r) { kernels::zero_columns(data, width, col_begin, col_end, r); });
}

void densify_stats_add_cuda(const float* view_grad_norm, const std::int32_t* radii, float ndc_scale,
                            float* grad_accum, float* denom, float* max_radii, size_t n) {
  parallel_for(Device::CUDA, n, [=] __device__(size_t i) {
    kernels::densify_stats_add(view_grad_norm, radii, ndc_scale, grad_accum, denom, max_radii, i);
  });
}

size_t first_non_finite_cuda(const float* data, size_t n) {
  const unsigned long long none = n;
  Buffer<unsigned long long> first(1, Device::CUDA);
  first.upload(&none, 1);
  unsigned long long* f = first.data();
  parallel_for(Device::CUDA, n, [=] __device__(size_t i) {
    if (!isfinite(data[i])) atomicMin(f, (unsigned long long)i);
  });
  unsigned long long out = none;
  first.download(&out);
  return size_t(out);
}

}  // namespace goris::detail
