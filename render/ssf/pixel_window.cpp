#include "render/ssf/pixel_window.h"

#include <algorithm>

#include "render/ssf/conv_cpu_blocked.h"

namespace goris::ssf {

PixelWindow net_window(const float* alpha, int width, int height, float threshold, int radius) {
  int bx0 = width, by0 = height, bx1 = -1, by1 = -1;  // inclusive bounds of the passing pixels
  for (int y = 0; y < height; ++y) {
    const float* row = alpha + std::size_t(y) * std::size_t(width);
    for (int x = 0; x < width; ++x)
      if (row[x] > threshold) {
        bx0 = std::min(bx0, x), bx1 = std::max(bx1, x);
        by0 = std::min(by0, y), by1 = std::max(by1, y);
      }
  }
  if (bx1 < 0) return {};
  PixelWindow w;
  w.x0 = std::max(0, bx0 - radius) / kPixBlock * kPixBlock;
  w.x1 = std::min(width, bx1 + 1 + radius + kPixBlock);
  w.y0 = std::max(0, by0 - radius);
  w.y1 = std::min(height, by1 + 1 + radius);
  return w;
}

}  // namespace goris::ssf
