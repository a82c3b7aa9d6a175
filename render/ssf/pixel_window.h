#pragma once
// A rectangle of pixels where the roughness net runs. The net's output at a pixel depends on its inputs within
// the receptive radius (one pixel per 3x3 layer), and the shading reads that output only on surface pixels
// (alpha > min_alpha), so evaluating the net on their bounding box grown by the radius gives every value the
// shading reads, bit for bit, and skips the background: on the suite's table scenes a third to half of the image.
#include "core/compute/hd.h"

namespace goris::ssf {

struct PixelWindow {  // columns [x0, x1), rows [y0, y1)
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  GORIS_HD int width() const { return x1 - x0; }
  GORIS_HD int height() const { return y1 - y0; }
  GORIS_HD bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool covers(int width_, int height_) const { return x0 <= 0 && y0 <= 0 && x1 >= width_ && y1 >= height_; }
};

// The window over an alpha image ([height][width], host memory) for a net of receptive radius `radius`: the
// bounding box of the pixels with alpha > threshold, grown by the radius and clamped to the image; empty when
// no pixel passes. The CPU's register-blocked convolutions (conv_cpu_blocked.h) work 4 pixels at a time from a
// row's start, and their parameter gradients sum those pixels in 4 lanes: the window starts on a multiple of 4
// and reaches 4 pixels further right, so that every sum the net's output and gradients need takes the same
// terms in the same order as on the whole image (zeros aside), and the results are identical.
PixelWindow net_window(const float* alpha, int width, int height, float threshold, int radius);

}  // namespace goris::ssf
