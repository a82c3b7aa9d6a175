#pragma once
// Per-element maths of the scene model, shared by the CPU driver (gaussians.cpp) and a CUDA twin.
// Templated on the scalar so the finite-difference tests can run the same code in double.
#include <cmath>
#include <cstddef>

#include "core/compute/hd.h"

namespace goris::kernels {

GORIS_HDI float exp_t(float x) { return expf(x); }
GORIS_HDI double exp_t(double x) { return ::exp(x); }
GORIS_HDI float log_t(float x) { return logf(x); }
GORIS_HDI double log_t(double x) { return ::log(x); }

template <class T>
GORIS_HDI T sigmoid(T x) {
  return T(1) / (T(1) + exp_t(-x));
}
template <class T>
GORIS_HDI T logit(T p) {
  return log_t(p / (T(1) - p));
}
// The logit of p clamped to [1e-3, 1 - 1e-3], so that colours and materials at 0 or 1 stay finite.
template <class T>
GORIS_HDI T logit_clamped(T p) {
  constexpr T kEps = T(1e-3);
  return logit(p < kEps ? kEps : (p > T(1) - kEps ? T(1) - kEps : p));
}

// Band-0 SH basis: colour = kShC0 x DC + 1/2 (render/math/sh.h holds the full basis for the renderers).
constexpr float kShC0 = 0.28209479177387814f;
// Between a DC coefficient and the colour it shows (T: a scalar or a glm vector); random_points alone
// writes it out, to keep its rounding.
template <class T>
GORIS_HDI T colour_from_sh_dc(T dc) {
  return T(kShC0) * dc + T(0.5f);
}
template <class T>
GORIS_HDI T sh_dc_from_colour(T colour) {
  return (colour - T(0.5f)) / T(kShC0);
}

// Activated extras and the chain rule back to the logits: d sigmoid / dx = s (1 - s). The activated-space
// gradient is consumed (zeroed) so the scratch is ready for the next backward pass.
template <class T>
GORIS_HDI void extras_forward(const T* logits, T* activated, size_t i) {
  activated[i] = sigmoid(logits[i]);
}
template <class T>
GORIS_HDI void extras_backward(const T* activated, T* activated_grad, T* logit_grad, size_t i) {
  const T s = activated[i];
  logit_grad[i] += activated_grad[i] * s * (T(1) - s);
  activated_grad[i] = T(0);
}

// The diffuse channel as the view-independent part of D (the SH colour): colour = C0 x DC + 1/2, its logit
// clamped as above. Gaussian i of `sh` ([N][sh_width], DC first) writes columns
// first..first+2 of `extra_logits` ([N][extras_width]).
template <class T>
GORIS_HDI void diffuse_from_sh_dc(const T* sh, int sh_width, T* extra_logits, int extras_width, int first, size_t i) {
  for (int c = 0; c < 3; ++c)
    extra_logits[i * size_t(extras_width) + size_t(first + c)] =
        logit_clamped(colour_from_sh_dc(sh[i * size_t(sh_width) + size_t(c)]));
}

}  // namespace goris::kernels
