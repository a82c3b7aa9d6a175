#pragma once
// OpenCV's diffusion inpainting (cv::inpaint): Telea's fast-marching method or Navier-Stokes. Each
// channel is filled on its own as a 32-bit float image (cv::inpaint takes CV_32FC1 at any range, but
// only 8-bit for 3 channels), so no precision is lost to 8-bit quantisation; values are scaled by 65536
// around the call because OpenCV's Telea adds an 8-bit rounding term of up to ~2 units to every filled
// pixel (a 200% error on [0, 1] data, see opencv_inpainter.cpp). About 25 ms per channel at 512x512
// (docs/design/architecture.md, Toolchain notes). The hole is the non-zero mask, as cv::inpaint expects. Both
// methods smear: a linear ramp across a 10-pixel hole comes back within ~2 pixels' worth of its slope, not
// exactly (use the harmonic inpainter for depth).
#include "core/inpaint/inpainter.h"

namespace goris {

class OpenCvInpainter final : public Inpainter {
 public:
  enum class Method { Telea, NavierStokes };
  // radius: the neighbourhood (pixels) each filled pixel draws from; > 0.
  explicit OpenCvInpainter(Method method, double radius = 3.0);
  std::string name() const override;
  Image fill(const Image& encoded, const Mask& hole, const MapInfo& info) const override;

 private:
  Method method_;
  double radius_;
};

}  // namespace goris
