#pragma once
// The roughness prefilter of the cube map as a chain of linear 1D steps: each level is the level above
// downsampled x1/2 along x, then along y, per face, with the binomial kernel [1 3 3 1] / 8 (a small
// Gaussian-like lobe folded into the downsample: blur [1 2 1] / 4 then a 2-box). Taps clamp at the face's
// edge. Cost per iteration: about 1.3 passes over the base level, so it can run after every step.
//
// The adjoint of one 1D step is written as a gather (each input sample sums the outputs that read it), so
// the backward pass needs no atomics and is deterministic.
#include <cstddef>

#include "core/compute/hd.h"

namespace goris::envmap {

// out[j] = sum_t w_t in[clamp(2j - 1 + t)], t = 0..3, for a line of n inputs (n even) read with `stride`.
template <class T>
GORIS_HDI T downsample_at(const T* in, int n, std::ptrdiff_t stride, int j) {
  const T w[4] = {T(0.125), T(0.375), T(0.375), T(0.125)};
  T s = T(0);
  for (int t = 0; t < 4; ++t) {
    int i = 2 * j - 1 + t;
    i = i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
    s += w[t] * in[i * stride];
  }
  return s;
}

// Adjoint of downsample_at at input sample i: sum over (j, t) with clamp(2j - 1 + t) == i of w_t gout[j],
// for the m = n / 2 outputs read with `stride`. Only j within two of i / 2 can reach i (clamped taps reach
// only i = 0 from j = 0 and i = n - 1 from j = m - 1, both inside that window).
template <class T>
GORIS_HDI T downsample_adjoint_at(const T* gout, int n, std::ptrdiff_t stride, int i) {
  const T w[4] = {T(0.125), T(0.375), T(0.375), T(0.125)};
  const int m = n / 2;
  const int j0 = i / 2 - 2 < 0 ? 0 : i / 2 - 2;
  const int j1 = i / 2 + 2 > m - 1 ? m - 1 : i / 2 + 2;
  T s = T(0);
  for (int j = j0; j <= j1; ++j)
    for (int t = 0; t < 4; ++t) {
      int k = 2 * j - 1 + t;
      k = k < 0 ? 0 : (k > n - 1 ? n - 1 : k);
      if (k == i) s += w[t] * gout[j * stride];
    }
  return s;
}

}  // namespace goris::envmap
