#include "removal/lift/surface_detail.h"

#include <cmath>
#include <cstddef>
#include <string>

#include "core/util/error.h"
#include "core/util/gaussian_filter.h"
#include "core/util/median.h"

namespace goris {

std::optional<double> surface_detail_rms(const Image& rgb, const std::vector<float>& glossy, const Mask& hole,
                                         const SurfaceDetailSettings& st) {
  const int w = rgb.width, h = rgb.height;
  const std::size_t n = std::size_t(w) * std::size_t(h);
  if (rgb.channels != 3 || glossy.size() != n || hole.width != w || hole.height != h)
    throw Error("surface detail", "the colour (" + std::to_string(w) + "x" + std::to_string(h) + "x" +
                                      std::to_string(rgb.channels) + "), the glossy mask (" +
                                      std::to_string(glossy.size()) + " values) and the hole (" +
                                      std::to_string(hole.width) + "x" + std::to_string(hole.height) +
                                      ") do not agree");
  const Mask grown = st.hole_margin > 0 ? dilate_mask(hole, st.hole_margin) : hole;
  std::vector<double> m(n), support(n), tmp(n);
  for (std::size_t p = 0; p < n; ++p) m[p] = glossy[p] >= 0.5f && !grown.data[p] ? 1.0 : 0.0;
  const std::vector<double> k = gaussian_kernel(st.sigma, int(std::ceil(3 * st.sigma)));
  gaussian_filter_zero_pad(m.data(), support.data(), tmp.data(), w, h, k);
  std::vector<bool> measured(n);
  std::size_t count = 0;
  for (std::size_t p = 0; p < n; ++p) count += (measured[p] = m[p] > 0 && support[p] >= st.min_support);
  if (count < std::size_t(st.min_pixels)) return std::nullopt;

  const std::vector<float> px = rgb.pixels.to_host();
  std::vector<double> x(n), blurred(n);
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t p = 0; p < n; ++p) x[p] = m[p] * px[p * 3 + std::size_t(c)];
    gaussian_filter_zero_pad(x.data(), blurred.data(), tmp.data(), w, h, k);
    for (std::size_t p = 0; p < n; ++p)
      if (measured[p]) {
        const double d = px[p * 3 + std::size_t(c)] - blurred[p] / support[p];
        sum += d * d;
      }
  }
  return std::sqrt(sum / double(3 * count));
}

std::optional<double> median_surface_detail(const std::vector<std::optional<double>>& per_view) {
  std::vector<double> v;
  for (const auto& d : per_view)
    if (d) v.push_back(*d);
  if (v.empty()) return std::nullopt;
  return median_of(std::move(v));
}

}  // namespace goris
