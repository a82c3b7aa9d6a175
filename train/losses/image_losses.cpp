#include "train/losses/image_losses.h"

#include <cmath>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace goris {

namespace {

constexpr int kWindow = 11, kRadius = 5;

template <class T>
const T* gaussian_window() {
  static const std::vector<T> w = [] {
    std::vector<double> g(kWindow);
    double sum = 0;
    for (int i = 0; i < kWindow; ++i) {
      const double d = i - kRadius;
      g[i] = std::exp(-d * d / (2.0 * 1.5 * 1.5));
      sum += g[i];
    }
    std::vector<T> out(kWindow);
    for (int i = 0; i < kWindow; ++i) out[i] = T(g[i] / sum);
    return out;
  }();
  return w.data();
}

// dst = window (x) window applied to src ([H][W]), zero outside the image. tmp has H*W elements.
template <class T>
void blur(const T* src, T* dst, T* tmp, int w, int h) {
  const T* g = gaussian_window<T>();
  tbb::parallel_for(0, h, [&](int y) {
    const T* row = src + size_t(y) * w;
    T* out = tmp + size_t(y) * w;
    for (int x = 0; x < w; ++x) {
      T s = 0;
      const int k0 = std::max(0, kRadius - x), k1 = std::min(kWindow, w - x + kRadius);
      for (int k = k0; k < k1; ++k) s += g[k] * row[x + k - kRadius];
      out[x] = s;
    }
  });
  tbb::parallel_for(0, h, [&](int y) {
    T* out = dst + size_t(y) * w;
    const int k0 = std::max(0, kRadius - y), k1 = std::min(kWindow, h - y + kRadius);
    for (int x = 0; x < w; ++x) out[x] = 0;
    for (int k = k0; k < k1; ++k) {
      const T gk = g[k];
      const T* in = tmp + size_t(y + k - kRadius) * w;
      for (int x = 0; x < w; ++x) out[x] += gk * in[x];
    }
  });
}

}  // namespace

template <class T>
T l1_loss(const T* pred, const T* target, size_t n, T* grad, T weight, const T* element_weight) {
  if (n == 0) return T(0);
  const auto w = [&](size_t i) { return element_weight ? element_weight[i] : T(1); };
  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 4096), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double acc) {
        for (size_t i = r.begin(); i != r.end(); ++i)
          acc += double(w(i)) * std::abs(double(pred[i]) - double(target[i]));
        return acc;
      },
      [](double a, double b) { return a + b; });
  if (grad) {
    const T g = weight / T(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        const T d = pred[i] - target[i];
        grad[i] += w(i) * (d > 0 ? g : (d < 0 ? -g : T(0)));
      }
    });
  }
  return T(sum / double(n));
}

template <class T>
T mse(const T* pred, const T* target, size_t n) {
  if (n == 0) return T(0);
  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 4096), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const double d = double(pred[i]) - double(target[i]);
          acc += d * d;
        }
        return acc;
      },
      [](double a, double b) { return a + b; });
  return T(sum / double(n));
}

double psnr_from_mse(double m) {
  if (m <= 0) return std::numeric_limits<double>::infinity();
  return -10.0 * std::log10(m);
}

template <class T>
T ssim(const T* pred, const T* target, int channels, int width, int height, T* grad, T weight) {
  const size_t hw = size_t(width) * size_t(height);
  if (hw == 0 || channels <= 0) return T(1);
  const T C1 = T(0.01 * 0.01), C2 = T(0.03 * 0.03);
  // Per channel: the five blurred moments, then the SSIM map and (for the gradient) three adjoint maps.
  std::vector<T> xx(hw), yy(hw), xy(hw), tmp(hw);
  std::vector<T> mu1(hw), mu2(hw), e11(hw), e22(hw), e12(hw);
  std::vector<T> d_mu(hw), d_e11(hw), d_e12(hw);
  const T gscale = weight / T(double(hw) * channels);
  double total = 0;
  for (int c = 0; c < channels; ++c) {
    const T* x = pred + c * hw;
    const T* y = target + c * hw;
    for (size_t i = 0; i < hw; ++i) {
      xx[i] = x[i] * x[i];
      yy[i] = y[i] * y[i];
      xy[i] = x[i] * y[i];
    }
    blur(x, mu1.data(), tmp.data(), width, height);
    blur(y, mu2.data(), tmp.data(), width, height);
    blur(xx.data(), e11.data(), tmp.data(), width, height);
    blur(yy.data(), e22.data(), tmp.data(), width, height);
    blur(xy.data(), e12.data(), tmp.data(), width, height);
    total += tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, hw, 4096), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double acc) {
          for (size_t i = r.begin(); i != r.end(); ++i) {
            const T m1 = mu1[i], m2 = mu2[i];
            const T A1 = T(2) * m1 * m2 + C1;
            const T A2 = T(2) * (e12[i] - m1 * m2) + C2;
            const T B1 = m1 * m1 + m2 * m2 + C1;
            const T B2 = (e11[i] - m1 * m1) + (e22[i] - m2 * m2) + C2;
            const T S = (A1 * A2) / (B1 * B2);
            acc += double(S);
            if (grad) {
              // S as a function of (mu1, e11, e12), with sigma1^2 = e11 - mu1^2 and sigma12 = e12 - mu1 mu2.
              const T inv = T(1) / (B1 * B2);
              d_mu[i] = gscale * ((T(2) * m2 * A2 - T(2) * m2 * A1) * inv - S * T(2) * m1 / B1 + S * T(2) * m1 / B2);
              d_e11[i] = gscale * (-S / B2);
              d_e12[i] = gscale * (T(2) * A1 * inv);
            }
          }
          return acc;
        },
        [](double a, double b) { return a + b; });
    if (grad) {
      // The adjoint of the blur is the blur itself; reuse the moment buffers as outputs.
      blur(d_mu.data(), mu1.data(), tmp.data(), width, height);
      blur(d_e11.data(), e11.data(), tmp.data(), width, height);
      blur(d_e12.data(), e12.data(), tmp.data(), width, height);
      T* g = grad + c * hw;
      tbb::parallel_for(tbb::blocked_range<size_t>(0, hw, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) g[i] += mu1[i] + T(2) * x[i] * e11[i] + y[i] * e12[i];
      });
    }
  }
  return T(total / (double(hw) * channels));
}

template <class T>
ColorLossParts color_loss(const T* pred, const T* target, int channels, int width, int height, T* grad,
                          T lambda_ssim, T weight) {
  const size_t n = size_t(channels) * size_t(width) * size_t(height);
  ColorLossParts p;
  p.l1 = double(l1_loss<T>(pred, target, n, grad, weight * (T(1) - lambda_ssim)));
  p.ssim = double(ssim<T>(pred, target, channels, width, height, grad, -weight * lambda_ssim));
  p.total = (1.0 - double(lambda_ssim)) * p.l1 + double(lambda_ssim) * (1.0 - p.ssim);
  return p;
}

ColorLossParts weighted_color_loss(const float* pred, const float* target, const float* weight, int w, int h,
                                   float* grad, float lambda_ssim, float scale) {
  const size_t hw = size_t(w) * size_t(h);
  std::vector<float> mixed(3 * hw), g(3 * hw, 0.0f);
  for (int c = 0; c < 3; ++c)
    for (size_t p = 0; p < hw; ++p) {
      const size_t i = c * hw + p;
      mixed[i] = weight[p] * pred[i] + (1 - weight[p]) * target[i];
    }
  const ColorLossParts parts = color_loss<float>(mixed.data(), target, 3, w, h, g.data(), lambda_ssim);
  for (int c = 0; c < 3; ++c)
    for (size_t p = 0; p < hw; ++p) grad[c * hw + p] += scale * weight[p] * g[c * hw + p];
  return parts;
}

#define GORIS_INSTANTIATE(T)                                                                               \
  template T l1_loss<T>(const T*, const T*, size_t, T*, T, const T*);                                      \
  template T mse<T>(const T*, const T*, size_t);                                                           \
  template T ssim<T>(const T*, const T*, int, int, int, T*, T);                                            \
  template ColorLossParts color_loss<T>(const T*, const T*, int, int, int, T*, T, T);
GORIS_INSTANTIATE(float)
GORIS_INSTANTIATE(double)
#undef GORIS_INSTANTIATE

}  // namespace goris
