#pragma once
// Image losses with their exact gradients, on planar host images ([C][H][W], row-major per channel), as the
// rasterizer's G-buffer lays them out. Templated on the scalar: float in training, double in the
// finite-difference tests. Gradients are ACCUMULATED (grad[i] += weight * dLoss/dpred[i]) so several
// losses can share one gradient image; pass grad = nullptr to only evaluate.
#include <cstddef>

namespace goris {

// mean |pred - target| over n values. d/dpred = sign(pred - target) / n (0 where they are equal).
// element_weight: null, or n weights w_i: mean w_i |pred_i - target_i| (still divided by n).
template <class T>
T l1_loss(const T* pred, const T* target, size_t n, T* grad = nullptr, T weight = T(1),
          const T* element_weight = nullptr);

// Mean squared error over n values (no gradient: metrics only).
template <class T>
T mse(const T* pred, const T* target, size_t n);

// PSNR in dB of an MSE for images in [0, 1]; +inf for a perfect match.
double psnr_from_mse(double mse);

// Mean SSIM over every pixel and channel, 3DGS / Wang et al.: 11x11 Gaussian window (sigma 1.5) applied as
// two separable 1D passes with zero padding ("same" size), C1 = 0.01^2, C2 = 0.03^2. The gradient with
// respect to pred is exact (the window's adjoint is itself: symmetric kernel, zero padding).
template <class T>
T ssim(const T* pred, const T* target, int channels, int width, int height, T* grad = nullptr, T weight = T(1));

// The 3DGS colour loss (1 - lambda) * L1 + lambda * (1 - SSIM), lambda = 0.2 by default. Also returns
// the two parts for logging.
struct ColorLossParts {
  double l1 = 0, ssim = 0, total = 0;
};
template <class T>
ColorLossParts color_loss(const T* pred, const T* target, int channels, int width, int height, T* grad = nullptr,
                          T lambda_ssim = T(0.2), T weight = T(1));

// The colour loss on the pixels a weight image ([H][W] in [0, 1]) selects: L(w pred + (1 - w) target, target),
// so pixels of weight 0 contribute neither loss nor gradient and SSIM windows see the target there;
// dL/dpred = w dL/dpred' (exact chain rule), scaled by `scale` and accumulated into grad. 3 channels.
ColorLossParts weighted_color_loss(const float* pred, const float* target, const float* weight, int w, int h,
                                   float* grad, float lambda_ssim, float scale);

}  // namespace goris
