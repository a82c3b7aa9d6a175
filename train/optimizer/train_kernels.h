#pragma once
// Per-element maths of the training loop shared by the CPU drivers and their CUDA twin.
#include <cstddef>
#include <cstdint>

#include "core/compute/hd.h"

namespace goris::kernels {

// One view's densification statistic for Gaussian i (only Gaussians the view sees count).
GORIS_HDI void densify_stats_add(const float* view_grad_norm, const std::int32_t* radii, float ndc_scale,
                                 float* grad_accum, float* denom, float* max_radii, size_t i) {
  if (radii[i] <= 0) return;
  grad_accum[i] += view_grad_norm[i] * ndc_scale;
  denom[i] += 1.0f;
  const float r = float(radii[i]);
  if (r > max_radii[i]) max_radii[i] = r;
}

GORIS_HDI void zero_columns(float* data, int width, int col_begin, int col_end, size_t row) {
  for (int c = col_begin; c < col_end; ++c) data[row * size_t(width) + size_t(c)] = 0.0f;
}

}  // namespace goris::kernels
