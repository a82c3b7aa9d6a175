#include "core/io/image.h"

#include <algorithm>
#include <system_error>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/file_bytes.h"
#include "core/util/error.h"

namespace goris {
namespace fs = std::filesystem;

namespace {


// Host-side float image <-> cv::Mat (the Mat shares the CPU buffer; no copy).
cv::Mat as_mat(Image& im) { return cv::Mat(im.height, im.width, CV_32FC(im.channels), im.pixels.data()); }

Image from_mat(const cv::Mat& m) {
  Image im(m.cols, m.rows, m.channels(), Device::CPU);
  cv::Mat dst = as_mat(im);
  m.copyTo(dst);
  return im;
}

Image host_copy(const Image& im) {
  Image h;
  h.width = im.width;
  h.height = im.height;
  h.channels = im.channels;
  h.pixels = im.pixels.copy_to(Device::CPU);
  return h;
}

Image to_device(Image im, Device d) {
  if (d == im.pixels.device()) return im;
  im.pixels = im.pixels.copy_to(d);
  return im;
}

}  // namespace

Image read_image(const fs::path& path) {
  require_regular_file(path, "image file");
  check_image_header_size(path);  // before the decoder allocates what the header declares
  cv::Mat raw;
  try {
    raw = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw Error(path.string(), std::string("cannot decode image: ") + e.what());
  }
  if (raw.empty()) throw Error(path.string(), "cannot decode image (corrupt file or unsupported format)");

  double scale = 1.0;
  switch (raw.depth()) {
    case CV_8U: scale = 1.0 / 255.0; break;
    case CV_16U: scale = 1.0 / 65535.0; break;
    case CV_32F:
    case CV_64F: scale = 1.0; break;
    default: throw Error(path.string(), "unsupported pixel type (expected 8- or 16-bit unsigned, or float)");
  }
  cv::Mat f;
  raw.convertTo(f, CV_32F, scale);
  cv::Mat rgb;
  switch (f.channels()) {
    case 1: rgb = f; break;
    case 2: {  // grey + alpha
      cv::Mat planes[2], rgba_planes[4];
      cv::split(f, planes);
      rgba_planes[0] = rgba_planes[1] = rgba_planes[2] = planes[0];
      rgba_planes[3] = planes[1];
      cv::merge(rgba_planes, 4, rgb);
      break;
    }
    case 3: cv::cvtColor(f, rgb, cv::COLOR_BGR2RGB); break;
    case 4: cv::cvtColor(f, rgb, cv::COLOR_BGRA2RGBA); break;
    default: throw Error(path.string(), "unsupported number of channels: " + std::to_string(f.channels()));
  }
  return from_mat(rgb);
}

namespace {

// The alpha channel of a decoded image (one channel, CPU), or nothing when it has none.
std::optional<Image> alpha_channel(const Image& src) {
  if (src.channels != 4) return std::nullopt;
  Image a(src.width, src.height, 1, Device::CPU);
  for (size_t i = 0; i < src.pixel_count(); ++i) a.pixels[i] = src.pixels[4 * i + 3];
  return a;
}

}  // namespace

Image load_image(const fs::path& path, Device device, glm::vec3 background, std::optional<Image>* alpha) {
  Image src = read_image(path);
  if (alpha) *alpha = alpha_channel(src);
  if (src.channels == 3) return to_device(std::move(src), device);
  Image out(src.width, src.height, 3, Device::CPU);
  const size_t n = src.pixel_count();
  const float* s = src.pixels.data();
  float* o = out.pixels.data();
  if (src.channels == 1) {
    for (size_t i = 0; i < n; ++i) o[3 * i] = o[3 * i + 1] = o[3 * i + 2] = s[i];
  } else {  // RGBA
    for (size_t i = 0; i < n; ++i) {
      const float a = s[4 * i + 3];
      for (int c = 0; c < 3; ++c) o[3 * i + c] = s[4 * i + c] * a + background[c] * (1.0f - a);
    }
  }
  return to_device(std::move(out), device);
}

Image load_mask(const fs::path& path, Device device) {
  Image src = read_image(path);
  if (src.channels == 1) return to_device(std::move(src), device);
  Image out(src.width, src.height, 1, Device::CPU);
  const size_t n = src.pixel_count();
  const int c = src.channels;
  const float* s = src.pixels.data();
  for (size_t i = 0; i < n; ++i) {
    const float* p = s + i * c;
    float v = std::max(p[0], std::max(p[1], p[2]));
    if (c == 4) v *= p[3];
    out.pixels[i] = v;
  }
  return to_device(std::move(out), device);
}

std::optional<Image> load_alpha(const fs::path& path, Device device) {
  std::optional<Image> alpha = alpha_channel(read_image(path));
  if (alpha) *alpha = to_device(std::move(*alpha), device);
  return alpha;
}

Image resize_image(const Image& image, int width, int height) {
  if (width <= 0 || height <= 0)
    throw Error("resize_image: invalid target size " + std::to_string(width) + "x" + std::to_string(height));
  Image src = host_copy(image);
  if (width == image.width && height == image.height) return to_device(std::move(src), image.pixels.device());
  const bool shrinking = width <= image.width && height <= image.height;
  Image dst(width, height, image.channels, Device::CPU);
  cv::Mat d = as_mat(dst);
  cv::resize(as_mat(src), d, cv::Size(width, height), 0, 0, shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);
  // cv::resize must write into our buffer, not reallocate.
  if (d.data != reinterpret_cast<uchar*>(dst.pixels.data())) throw Error("resize_image: internal buffer mismatch");
  return to_device(std::move(dst), image.pixels.device());
}

void save_png(const fs::path& path, const Image& image, bool sixteen_bit) {
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    throw Error(path.string(), "cannot save an image with " + std::to_string(image.channels) +
                                   " channels as PNG (1, 3 or 4 expected)");
  if (image.width <= 0 || image.height <= 0) throw Error(path.string(), "cannot save an empty image");
  Image h = host_copy(image);
  cv::Mat f = as_mat(h);
  // Clamp (NaN becomes 0) before quantising.
  f.forEach<float>([](float& v, const int*) { v = v >= 0.0f ? (v <= 1.0f ? v : 1.0f) : 0.0f; });
  cv::Mat q;
  f.convertTo(q, sixteen_bit ? CV_16U : CV_8U, sixteen_bit ? 65535.0 : 255.0);
  if (q.channels() == 3) cv::cvtColor(q, q, cv::COLOR_RGB2BGR);
  if (q.channels() == 4) cv::cvtColor(q, q, cv::COLOR_RGBA2BGRA);
  std::vector<uchar> png;
  try {
    if (!cv::imencode(".png", q, png)) throw Error(path.string(), "cannot encode PNG");
  } catch (const cv::Exception& e) {
    throw Error(path.string(), std::string("cannot encode PNG: ") + e.what());
  }
  write_file_bytes(path, png.data(), png.size());
}

}  // namespace goris
