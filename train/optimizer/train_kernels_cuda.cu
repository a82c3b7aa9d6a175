// CUDA twin of the training loop's per-element kernels (maths in adam_kernel.h and train_kernels.h).
#include "core/compute/buffer.h"
#include "core/compute/parallel_for.h"
#include "train/optimizer/adam_kernel.h"
#include "train/optimizer/train_cuda.h"
#include "train/optimizer/train_kernels.h"

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

}  // namespace goris::detail
