#include "render/maps/gbuffer_maps.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace goris {

Image depth_to_turbo(const float* depth, const float* alpha, int width, int height, bool depth_is_weighted,
                     float min_alpha) {
  const size_t hw = size_t(width) * size_t(height);
  std::vector<float> inv(hw, -1.0f), valid;
  for (size_t p = 0; p < hw; ++p) {
    const float a = alpha ? alpha[p] : 1.0f;
    if (a <= min_alpha) continue;
    const float d = depth_is_weighted ? depth[p] / a : depth[p];
    if (!(d > 0) || !std::isfinite(d)) continue;
    inv[p] = 1.0f / d;
    valid.push_back(inv[p]);
  }
  Image img(width, height, 3, Device::CPU);
  img.pixels.fill_zero();
  if (valid.empty()) return img;
  std::sort(valid.begin(), valid.end());
  const float lo = valid[size_t(0.01 * double(valid.size() - 1))];
  const float hi = valid[size_t(0.99 * double(valid.size() - 1))];
  const float range = hi > lo ? hi - lo : 1.0f;
  cv::Mat grey(height, width, CV_8UC1), colour;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float v = inv[size_t(y) * width + x];
      grey.at<uint8_t>(y, x) = uint8_t(std::lround(255.0f * std::clamp((v - lo) / range, 0.0f, 1.0f)));
    }
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);  // BGR
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * width + x;
      if (inv[p] < 0) continue;
      const cv::Vec3b bgr = colour.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) img.pixels[p * 3 + c] = float(bgr[2 - c]) / 255.0f;
    }
  return img;
}

Image normals_to_rgb(const float* normal, const float* alpha, int width, int height, float min_alpha) {
  const size_t hw = size_t(width) * size_t(height);
  Image img(width, height, 3, Device::CPU);
  img.pixels.fill_zero();
  for (size_t p = 0; p < hw; ++p) {
    if (alpha && alpha[p] <= min_alpha) continue;
    const float n[3] = {normal[p], normal[hw + p], normal[2 * hw + p]};
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) continue;
    for (int c = 0; c < 3; ++c) img.pixels[p * 3 + c] = n[c] / len * 0.5f + 0.5f;
  }
  return img;
}

}  // namespace goris
