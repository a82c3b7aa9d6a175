#include "render/removal/lighting_aware_mask.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/error.h"

namespace goris {

Mask lighting_aware_mask(const std::vector<float>& e, int width, int height, const LightingMaskSettings& s) {
  if (width <= 0 || height <= 0 || e.size() != std::size_t(width) * std::size_t(height))
    throw Error("lighting-aware mask", "the reflected-label image holds " + std::to_string(e.size()) +
                                           " values for a " + std::to_string(width) + "x" + std::to_string(height) +
                                           " view");
  if (!(s.tau >= 0) || !std::isfinite(s.tau)) throw Error("lighting-aware mask", "tau must be finite and >= 0");
  Mask m(width, height);
  for (std::size_t p = 0; p < e.size(); ++p) {
    if (!std::isfinite(e[p])) throw Error("lighting-aware mask", "non-finite reflected label at pixel " + std::to_string(p));
    m.data[p] = e[p] > s.tau ? 255 : 0;
  }
  const int r = s.dilate >= 0 ? s.dilate : std::max(1, int(std::lround(width / 128.0)));
  return dilate_mask(m, r);
}

}  // namespace goris
