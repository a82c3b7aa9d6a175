#include "removal/lift/photo_under_reflection.h"

#include <cmath>
#include <string>

#include "core/util/error.h"

namespace goris {

Mask reflection_left_to_the_fill(const Mask& reflection, const Mask& lighting, const Mask& silhouette,
                                 const std::vector<float>& photo, const Image& fill, double detail,
                                 const PhotoUnderReflectionSettings& st, std::size_t* kept) {
  const int w = reflection.width, h = reflection.height;
  const std::size_t n = std::size_t(w) * std::size_t(h);
  auto same = [&](const Mask& m) { return m.width == w && m.height == h; };
  if (!same(lighting) || !same(silhouette) || photo.size() != 3 * n || fill.width != w || fill.height != h ||
      fill.channels != 3)
    throw Error("photo under the reflection",
                "the reflection mask (" + std::to_string(w) + "x" + std::to_string(h) + "), the lighting-aware mask, the "
                "silhouette, the photo (" + std::to_string(photo.size()) + " values) and the fill (" +
                std::to_string(fill.width) + "x" + std::to_string(fill.height) + "x" + std::to_string(fill.channels) +
                ") do not agree");
  Mask left = reflection;
  std::size_t count = 0;
  const double tau = st.texture_multiple * detail;
  if (detail > 0 && tau > 0) {
    const Mask near = st.silhouette_margin > 0 ? dilate_mask(silhouette, st.silhouette_margin) : silhouette;
    const std::vector<float> f = fill.pixels.to_host();
    for (std::size_t p = 0; p < n; ++p) {
      if (!left.data[p] || !lighting.data[p] || near.data[p]) continue;
      double d = 0;
      for (std::size_t c = 0; c < 3; ++c) d += std::abs(double(photo[c * n + p]) - double(f[p * 3 + c]));
      if (d / 3 <= tau) left.data[p] = 0, ++count;
    }
  }
  if (kept) *kept = count;
  return left;
}

}  // namespace goris
