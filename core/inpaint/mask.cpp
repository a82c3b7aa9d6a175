#include "core/inpaint/mask.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "core/util/error.h"

namespace goris {

namespace {

cv::Mat as_mat(const Mask& m) { return cv::Mat(m.height, m.width, CV_8UC1, const_cast<std::uint8_t*>(m.data.data())); }

Mask from_mat(const cv::Mat& mat) {
  Mask m(mat.cols, mat.rows);
  for (int y = 0; y < mat.rows; ++y)
    for (int x = 0; x < mat.cols; ++x) m.set(x, y, mat.at<std::uint8_t>(y, x) != 0);
  return m;
}

cv::Mat square(int radius) { return cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius + 1, 2 * radius + 1)); }

void check_same_size(const Mask& a, const Mask& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw Error(std::string(what) + ": masks of different sizes (" + std::to_string(a.width) + "x" +
                std::to_string(a.height) + " and " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

// Erosion/dilation with OpenCV's default border values: outside pixels are +inf for erosion (set) and
// -inf for dilation (unset).
Mask morph(const Mask& mask, int radius, int op) {
  if (radius < 0) throw Error("mask morphology: negative radius " + std::to_string(radius));
  if (radius == 0 || mask.pixel_count() == 0) return mask;
  cv::Mat out;
  cv::morphologyEx(as_mat(mask), out, op, square(radius));
  return from_mat(out);
}

}  // namespace

std::size_t count_set(const Mask& mask) {
  return std::size_t(std::count_if(mask.data.begin(), mask.data.end(), [](std::uint8_t v) { return v != 0; }));
}

Mask open_mask(const Mask& mask, int radius) { return morph(mask, radius, cv::MORPH_OPEN); }
Mask close_mask(const Mask& mask, int radius) { return morph(mask, radius, cv::MORPH_CLOSE); }
Mask dilate_mask(const Mask& mask, int radius) { return morph(mask, radius, cv::MORPH_DILATE); }

Mask mask_and(const Mask& a, const Mask& b) {
  check_same_size(a, b, "mask_and");
  Mask m(a.width, a.height);
  for (std::size_t i = 0; i < m.data.size(); ++i) m.data[i] = a.data[i] && b.data[i] ? 255 : 0;
  return m;
}

Mask mask_or(const Mask& a, const Mask& b) {
  check_same_size(a, b, "mask_or");
  Mask m(a.width, a.height);
  for (std::size_t i = 0; i < m.data.size(); ++i) m.data[i] = a.data[i] || b.data[i] ? 255 : 0;
  return m;
}

Image mask_to_image(const Mask& mask) {
  Image img(mask.width, mask.height, 1, Device::CPU);
  for (std::size_t i = 0; i < mask.data.size(); ++i) img.pixels[i] = mask.data[i] ? 1.0f : 0.0f;
  return img;
}

Mask mask_from_image(const Image& image, float threshold) {
  if (image.channels < 1) throw Error("mask_from_image: an image with no channels");
  const std::vector<float> px = image.pixels.to_host();
  Mask m(image.width, image.height);
  for (std::size_t i = 0; i < m.data.size(); ++i) m.data[i] = px[i * std::size_t(image.channels)] > threshold ? 255 : 0;
  return m;
}

void save_mask_png(const std::filesystem::path& path, const Mask& mask) { save_png(path, mask_to_image(mask)); }

Mask read_mask_png(const std::filesystem::path& path) { return mask_from_image(read_image(path), 127.5f / 255.0f); }

int soft_edge_radius(int width) { return std::max(1, int(std::lround(width / 128.0))); }

}  // namespace goris
