#include "core/inpaint/opencv_inpainter.h"

#include <string>

#include <opencv2/photo.hpp>

#include "core/inpaint/map_encoding.h"
#include "core/util/error.h"

namespace goris {

namespace {
// OpenCV's Telea step ends with `Ia/s + (Jx+Jy)/|J| + 0.5` before the store: an additive term of up to
// ~1.9 in the image's units, meant as rounding for 8-bit data. On [0, 1] floats that is a 200% error,
// so values are scaled up by this factor first (the fill is linear in the values) and back after.
constexpr float kScale = 65536.0f;
}  // namespace

OpenCvInpainter::OpenCvInpainter(Method method, double radius) : method_(method), radius_(radius) {
  if (!(radius > 0)) throw Error("OpenCV inpainting: the radius must be positive, got " + std::to_string(radius));
}

std::string OpenCvInpainter::name() const {
  return std::string(method_ == Method::Telea ? "opencv-telea" : "opencv-ns") + " (radius " +
         std::to_string(int(radius_ + 0.5)) + ")";
}

Image OpenCvInpainter::fill(const Image& encoded, const Mask& hole, const MapInfo& info) const {
  const int W = encoded.width, H = encoded.height, C = encoded.channels;
  const cv::Mat mask(H, W, CV_8UC1, const_cast<std::uint8_t*>(hole.data.data()));
  const std::vector<float> in = encoded.pixels.to_host();
  Image out(W, H, C, Device::CPU);
  cv::Mat channel(H, W, CV_32FC1), filled;
  const int flags = method_ == Method::Telea ? cv::INPAINT_TELEA : cv::INPAINT_NS;
  for (int c = 0; c < C; ++c) {
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) channel.at<float>(y, x) = kScale * in[(std::size_t(y) * W + x) * C + c];
    try {
      cv::inpaint(channel, mask, filled, radius_, flags);
    } catch (const cv::Exception& e) {
      throw Error(map_label(info), name() + " failed: " + e.what());
    }
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) out.pixels[(std::size_t(y) * W + x) * C + c] = filled.at<float>(y, x) / kScale;
  }
  return out;
}

}  // namespace goris
