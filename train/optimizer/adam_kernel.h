#pragma once
// One Adam update of one element (Kingma & Ba, bias-corrected; the form torch.optim.Adam uses), shared by
// the CPU driver (adam.cpp) and its CUDA twin.
#include <cmath>
#include <cstddef>

#include "core/compute/hd.h"

namespace goris::kernels {

struct AdamStep {
  float lr = 0, beta1 = 0.9f, beta2 = 0.999f, eps = 1e-15f;
  float bias1 = 1, bias2 = 1;  // 1 - beta1^t, 1 - beta2^t for this step t >= 1
  // The group spans columns [col_begin, col_begin + group_width) of rows `width` wide.
  int width = 1, col_begin = 0, group_width = 1;
};

GORIS_HDI void adam_update(float& p, float& m, float& v, float g, const AdamStep& s) {
  m = s.beta1 * m + (1.0f - s.beta1) * g;
  v = s.beta2 * v + (1.0f - s.beta2) * g * g;
  const float denom = sqrtf(v) / sqrtf(s.bias2) + s.eps;
  p -= (s.lr / s.bias1) * m / denom;
}

// Every element of the group in row `row` (one work item per row: no index division per element).
GORIS_HDI void adam_group_row(float* p, float* m, float* v, const float* g, const AdamStep& s, size_t row) {
  const size_t k0 = row * size_t(s.width) + size_t(s.col_begin);
  for (int c = 0; c < s.group_width; ++c) adam_update(p[k0 + c], m[k0 + c], v[k0 + c], g[k0 + c], s);
}

}  // namespace goris::kernels
