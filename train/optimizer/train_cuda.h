#pragma once
// CUDA entry points of the training kernels (train_kernels_cuda.cu), called through GORIS_CUDA_CALL.
#include <cstddef>
#include <cstdint>

#include "train/optimizer/adam_kernel.h"

namespace goris::detail {
void adam_step_cuda(float* p, float* m, float* v, const float* g, const kernels::AdamStep& s, size_t rows);
void zero_columns_cuda(float* data, int width, int col_begin, int col_end, size_t rows);
void densify_stats_add_cuda(const float* view_grad_norm, const std::int32_t* radii, float ndc_scale,
                            float* grad_accum, float* denom, float* max_radii, size_t n);
}  // namespace goris::detail
