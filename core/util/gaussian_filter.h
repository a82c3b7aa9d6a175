#pragma once
// A normalised 1D Gaussian kernel and the separable 2D filter with it, zero outside the image (a "same"
// size conv2d). Planes are [H][W] doubles.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace goris {

// 2 * radius + 1 taps of exp(-d^2 / (2 sigma^2)), summing to 1.
inline std::vector<double> gaussian_kernel(double sigma, int radius) {
  std::vector<double> k(std::size_t(2 * radius + 1));
  double sum = 0;
  for (int i = -radius; i <= radius; ++i) sum += k[std::size_t(i + radius)] = std::exp(-double(i * i) / (2 * sigma * sigma));
  for (double& v : k) v /= sum;
  return k;
}

// dst = src filtered along rows, then columns, by kernel k (odd length); tmp: a w*h scratch plane.
inline void gaussian_filter_zero_pad(const double* src, double* dst, double* tmp, int w, int h,
                                     const std::vector<double>& k) {
  const int r = int(k.size() / 2);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double acc = 0;
      for (int i = std::max(0, r - x); i < int(k.size()) && x + i - r < w; ++i) acc += k[std::size_t(i)] * src[std::size_t(y) * w + x + i - r];
      tmp[std::size_t(y) * w + x] = acc;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double acc = 0;
      for (int i = std::max(0, r - y); i < int(k.size()) && y + i - r < h; ++i) acc += k[std::size_t(i)] * tmp[std::size_t(y + i - r) * w + x];
      dst[std::size_t(y) * w + x] = acc;
    }
}

}  // namespace goris
