#include "removal/masks/planar_dereflect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "core/util/error.h"

namespace goris {

std::vector<float> gaussian_blur_planar(const std::vector<float>& image, int channels, int width, int height,
                                        float sigma) {
  const std::size_t hw = std::size_t(width) * std::size_t(height);
  if (image.size() != std::size_t(channels) * hw)
    throw Error("blur", "the image has " + std::to_string(image.size()) + " values for " + std::to_string(channels) +
                            " x " + std::to_string(width) + " x " + std::to_string(height));
  if (!(sigma > 0.0f)) return image;
  std::vector<float> out(image.size());
  for (int c = 0; c < channels; ++c) {
    const cv::Mat src(height, width, CV_32F, const_cast<float*>(image.data() + c * hw));
    cv::Mat dst(height, width, CV_32F, out.data() + c * hw);
    cv::GaussianBlur(src, dst, cv::Size(0, 0), double(sigma), double(sigma), cv::BORDER_REFLECT);
  }
  return out;
}

PlanarDereflectFit dereflect_planar_reflection(std::vector<float>& photo, const std::vector<float>& smooth,
                                               const std::vector<float>& delta, const Mask& region,
                                               const PlanarDereflectSettings& settings) {
  const std::size_t hw = region.pixel_count();
  if (photo.size() != 3 * hw || smooth.size() != 3 * hw || delta.size() != 3 * hw)
    throw Error("planar dereflection", "photo (" + std::to_string(photo.size()) + "), smooth fill (" +
                                           std::to_string(smooth.size()) + "), reflection (" +
                                           std::to_string(delta.size()) + ") and region (3 x " + std::to_string(hw) +
                                           ") differ in size");
  PlanarDereflectFit best;
  best.pixels = count_set(region);
  if (best.pixels == 0) return best;
  std::vector<float> best_delta;
  for (const float fraction : settings.blur_fractions) {
    const float sigma = fraction * float(region.width);
    std::vector<float> d = gaussian_blur_planar(delta, 3, region.width, region.height, sigma);
    double rd = 0, dd = 0, rr = 0;
    for (std::size_t p = 0; p < hw; ++p) {
      if (!region.data[p]) continue;
      for (int c = 0; c < 3; ++c) {
        const double r = double(photo[c * hw + p]) - double(smooth[c * hw + p]), x = d[c * hw + p];
        rd += r * x, dd += x * x, rr += r * r;
      }
    }
    if (!(dd > 0.0) || !(rr > 0.0)) continue;
    const double scale = std::clamp(rd / dd, 0.0, double(settings.max_reflectance));
    // |r - s d|^2 = rr - 2 s rd + s^2 dd
    const double explained = 1.0 - (rr - 2.0 * scale * rd + scale * scale * dd) / rr;
    if (best_delta.empty() || explained > double(best.explained)) {
      best.reflectance = float(scale), best.blur = sigma, best.explained = float(explained);
      best_delta = std::move(d);
    }
  }
  if (best_delta.empty() || !(best.reflectance > 0.0f) || best.explained < settings.min_explained) return best;
  best.applied = true;
  for (std::size_t p = 0; p < hw; ++p) {
    if (!region.data[p]) continue;
    for (int c = 0; c < 3; ++c) {
      float& v = photo[c * hw + p];
      v = std::clamp(v - best.reflectance * best_delta[c * hw + p], 0.0f, 1.0f);
    }
  }
  return best;
}

}  // namespace goris
