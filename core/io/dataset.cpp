#include "core/io/dataset.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/util/error.h"

namespace goris {

ImageSize scaled_size(int width, int height, const DatasetOptions& o) {
  if (o.target_width > 0) {
    const int h = int(std::lround(double(height) * o.target_width / width));
    return {o.target_width, std::max(1, h)};
  }
  return {std::max(1, int(std::lround(width / double(o.downscale)))),
          std::max(1, int(std::lround(height / double(o.downscale))))};
}

SceneBounds camera_bounds(const std::vector<View>& views) {
  SceneBounds b;
  if (views.empty()) return b;
  glm::dvec3 sum(0.0);
  for (const View& v : views) sum += glm::dvec3(v.camera.center());
  b.center = glm::vec3(sum / double(views.size()));
  float r = 0;
  for (const View& v : views) r = std::max(r, glm::length(v.camera.center() - b.center));
  b.radius = 1.1f * r;
  return b;
}

std::vector<Camera> cameras_of(const std::vector<View>& views) {
  std::vector<Camera> c;
  c.reserve(views.size());
  for (const View& v : views) c.push_back(v.camera);
  return c;
}

SceneBounds Dataset::camera_bounds() const { return goris::camera_bounds(train.empty() ? test : train); }

Image undistort_image(const Image& image, const Camera& pinhole, const Distortion& lens) {
  // For each pixel of the pinhole image, where the distorted image holds it (OpenCV's model, the camera's
  // own): the same intrinsics before and after, so the image keeps its size and its centre.
  const cv::Matx33d k(pinhole.fx, 0, pinhole.cx, 0, pinhole.fy, pinhole.cy, 0, 0, 1);
  const cv::Vec<double, 5> d(lens.k1, lens.k2, lens.p1, lens.p2, lens.k3);
  cv::Mat map1, map2;
  cv::initUndistortRectifyMap(k, d, cv::Matx33d::eye(), k, cv::Size(image.width, image.height), CV_32FC1, map1, map2);
  const std::vector<float> px = image.pixels.to_host();
  const cv::Mat src(image.height, image.width, CV_32FC(image.channels), const_cast<float*>(px.data()));
  cv::Mat dst;
  // Pixels the distorted image does not reach (corners under barrel distortion) repeat its border.
  cv::remap(src, dst, map1, map2, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  Image out(image.width, image.height, image.channels, Device::CPU);
  std::copy(dst.ptr<float>(), dst.ptr<float>() + px.size(), out.pixels.data());
  return out;
}

namespace {

// The file must still be the size the data set was loaded with; then it is resampled to the camera's size.
Image fit_to_view(Image im, const std::filesystem::path& file, const View& v, Device device) {
  if (im.width != v.source_width || im.height != v.source_height)
    throw Error(file.string(), "is " + std::to_string(im.width) + "x" + std::to_string(im.height) + ", expected " +
                                   std::to_string(v.source_width) + "x" + std::to_string(v.source_height) +
                                   " (did the file change after the data set was loaded?)");
  Image out = resize_image(im, v.camera.width, v.camera.height);
  if (v.lens.any()) out = undistort_image(out, v.camera, v.lens);
  if (device != Device::CPU) out.pixels = out.pixels.copy_to(device);
  return out;
}

const std::filesystem::path& require(const std::optional<std::filesystem::path>& p, const View& v, const char* what) {
  if (!p) throw Error(v.image.string(), std::string("has no ") + what);
  return *p;
}

}  // namespace

Image load_view_image(const View& v, const DatasetOptions& o, Device device, std::optional<Image>* alpha) {
  Image im = fit_to_view(load_image(v.image, Device::CPU, o.background, alpha), v.image, v, device);
  if (alpha && *alpha) **alpha = fit_to_view(std::move(**alpha), v.image, v, Device::CPU);
  return im;
}

Image load_view_object_mask(const View& v, Device device) {
  const auto& p = require(v.object_mask, v, "object mask");
  return fit_to_view(load_mask(p, Device::CPU), p, v, device);
}

Image load_view_glossy_mask(const View& v, Device device) {
  const auto& p = require(v.glossy_mask, v, "glossy-surface mask");
  return fit_to_view(load_mask(p, Device::CPU), p, v, device);
}

Image load_view_full_image(const View& v, const DatasetOptions& o, Device device) {
  const auto& p = require(v.full_image, v, "full_ image (the view with the target)");
  return fit_to_view(load_image(p, Device::CPU, o.background), p, v, device);
}

}  // namespace goris
