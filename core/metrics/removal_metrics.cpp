// Changed-region metrics of an object removal; see removal_metrics.h.
#include "core/metrics/removal_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/util/gaussian_filter.h"

namespace goris {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check(const float* p, int w, int h, const char* what) {
  if (!p) throw std::invalid_argument(std::string(what) + ": null image");
  if (w <= 0 || h <= 0) throw std::invalid_argument(std::string(what) + ": empty image");
}

// Median of each (2r + 1)^2 window of one [H][W] plane, clamp-to-edge.
std::vector<float> median_plane(const float* src, int w, int h, int r) {
  std::vector<float> out(size_t(w) * h), win;
  win.reserve(size_t(2 * r + 1) * (2 * r + 1));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      win.clear();
      for (int dy = -r; dy <= r; ++dy) {
        const float* row = src + size_t(std::clamp(y + dy, 0, h - 1)) * w;
        for (int dx = -r; dx <= r; ++dx) win.push_back(row[std::clamp(x + dx, 0, w - 1)]);
      }
      auto mid = win.begin() + win.size() / 2;
      std::nth_element(win.begin(), mid, win.end());
      out[size_t(y) * w + x] = *mid;
    }
  return out;
}

// Binary dilation by a (2r + 1)^2 square: a row max then a column max.
std::vector<uint8_t> dilate_square(const std::vector<uint8_t>& m, int w, int h, int r) {
  std::vector<uint8_t> rows(m.size()), out(m.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t v = 0;
      for (int dx = std::max(0, x - r); dx <= std::min(w - 1, x + r) && !v; ++dx) v = m[size_t(y) * w + dx];
      rows[size_t(y) * w + x] = v;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t v = 0;
      for (int dy = std::max(0, y - r); dy <= std::min(h - 1, y + r) && !v; ++dy) v = rows[size_t(dy) * w + x];
      out[size_t(y) * w + x] = v;
    }
  return out;
}

}  // namespace

ChangedRegion changed_region(const float* before, const float* after, int width, int height,
                             const ChangedRegionOptions& options) {
  check(before, width, height, "changed_region");
  check(after, width, height, "changed_region");
  const size_t n = size_t(width) * height;
  const int mr = options.median > 1 ? options.median / 2 : 0;
  std::vector<float> diff(n, 0.0f);
  for (int c = 0; c < 3; ++c) {
    const float* b = before + c * n;
    const float* a = after + c * n;
    std::vector<float> mb, ma;
    if (mr > 0) {
      mb = median_plane(b, width, height, mr);
      ma = median_plane(a, width, height, mr);
      b = mb.data();
      a = ma.data();
    }
    for (size_t p = 0; p < n; ++p) diff[p] = std::max(diff[p], std::abs(b[p] - a[p]));
  }
  ChangedRegion region;
  region.mask.resize(n);
  for (size_t p = 0; p < n; ++p) region.mask[p] = diff[p] > options.threshold ? 1 : 0;
  if (options.dilate > 0) region.mask = dilate_square(region.mask, width, height, options.dilate);
  size_t count = 0;
  for (uint8_t v : region.mask) count += v;
  region.fraction = double(count) / double(n);
  return region;
}

std::vector<float> ssim_map(const float* a, const float* b, int width, int height, int channels) {
  check(a, width, height, "ssim_map");
  check(b, width, height, "ssim_map");
  constexpr int kWindow = 11;
  constexpr double kSigma = 1.5, kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;
  const std::vector<double> k = gaussian_kernel(kSigma, kWindow / 2);

  const size_t n = size_t(width) * height;
  std::vector<double> x(n), y(n), xx(n), yy(n), xy(n), tmp(n);
  std::vector<double> mx(n), my(n), sxx(n), syy(n), sxy(n), acc(n, 0.0);
  for (int c = 0; c < channels; ++c) {
    for (size_t p = 0; p < n; ++p) {
      x[p] = a[c * n + p];
      y[p] = b[c * n + p];
      xx[p] = x[p] * x[p];
      yy[p] = y[p] * y[p];
      xy[p] = x[p] * y[p];
    }
    gaussian_filter_zero_pad(x.data(), mx.data(), tmp.data(), width, height, k);
    gaussian_filter_zero_pad(y.data(), my.data(), tmp.data(), width, height, k);
    gaussian_filter_zero_pad(xx.data(), sxx.data(), tmp.data(), width, height, k);
    gaussian_filter_zero_pad(yy.data(), syy.data(), tmp.data(), width, height, k);
    gaussian_filter_zero_pad(xy.data(), sxy.data(), tmp.data(), width, height, k);
    for (size_t p = 0; p < n; ++p) {
      const double m1 = mx[p], m2 = my[p];
      const double v1 = sxx[p] - m1 * m1, v2 = syy[p] - m2 * m2, cov = sxy[p] - m1 * m2;
      acc[p] += (2 * m1 * m2 + kC1) * (2 * cov + kC2) / ((m1 * m1 + m2 * m2 + kC1) * (v1 + v2 + kC2));
    }
  }
  std::vector<float> out(n);
  for (size_t p = 0; p < n; ++p) out[p] = float(acc[p] / channels);
  return out;
}

double region_residual(const float* a, const float* b, const std::vector<uint8_t>& region, int width, int height,
                       int median) {
  check(a, width, height, "region_residual");
  check(b, width, height, "region_residual");
  const size_t n = size_t(width) * height;
  if (region.size() != n) throw std::invalid_argument("region_residual: the region is not the images' size");
  const int mr = median > 1 ? median / 2 : 0;
  double sum = 0;
  auto plane = [&](const float* img, int c) {
    const float* p = img + size_t(c) * n;
    return mr > 0 ? median_plane(p, width, height, mr) : std::vector<float>(p, p + n);
  };
  for (int c = 0; c < 3; ++c) {
    const std::vector<float> fa = plane(a, c), fb = plane(b, c);
    for (size_t p = 0; p < n; ++p)
      if (region[p]) sum += std::abs(double(fa[p]) - fb[p]);
  }
  return sum;
}

RemovalMetrics removal_metrics(const float* render, const float* after, const float* before, int width, int height,
                               const ChangedRegionOptions& options, double ppd) {
  check(render, width, height, "removal_metrics");
  const size_t n = size_t(width) * height;
  RemovalMetrics m;
  ChangedRegion region = changed_region(before, after, width, height, options);
  m.region_fraction = region.fraction;
  m.region = std::move(region.mask);

  const std::vector<float> flip_map = flip_error_map(render, after, width, height, ppd, &m.flip);
  size_t count = 0;
  double se = 0, ssim_sum = 0, flip_sum = 0;
  const std::vector<float> ssim = ssim_map(render, after, width, height, 3);
  for (size_t p = 0; p < n; ++p) {
    if (!m.region[p]) continue;
    ++count;
    for (int c = 0; c < 3; ++c) {
      const double d = double(render[c * n + p]) - after[c * n + p];
      se += d * d;
    }
    ssim_sum += ssim[p];
    flip_sum += flip_map[p];
  }
  if (count == 0) {
    m.region_psnr = m.region_ssim = m.ghost_ratio = m.region_flip = kNaN;
    return m;
  }
  // The ghost compares the images after the region's median: the ground truth's path-tracing noise is in
  // |render - after| wherever the render is clean, and would count as ghost on a dim reflection.
  const double ghost_num = region_residual(render, after, m.region, width, height, options.median);
  const double ghost_den = region_residual(before, after, m.region, width, height, options.median);
  const double mse = se / double(3 * count);
  m.region_psnr = mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
  m.region_ssim = ssim_sum / double(count);
  m.region_flip = flip_sum / double(count);
  constexpr double kGhostEps = 1e-9;  // before == after over the region: the ratio means nothing
  m.ghost_ratio = ghost_den > kGhostEps ? ghost_num / ghost_den : kNaN;
  m.ghost_residual = ghost_num, m.ghost_imprint = ghost_den;
  return m;
}

}  // namespace goris
