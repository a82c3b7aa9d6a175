#pragma once
// Images as float buffers on one device. Values are the file's values scaled to [0, 1] (8-bit / 255,
// 16-bit / 65535, float files as they are) with NO gamma change: an sRGB-encoded PNG stays sRGB-encoded,
// exactly what the photos' loss functions compare against.
#include <cstdint>
#include <filesystem>
#include <optional>

#include <glm/glm.hpp>

#include "core/compute/buffer.h"

namespace goris {

// Row-major, interleaved channels (HWC): pixel (x, y) channel c is pixels[(y * width + x) * channels + c].
// Channel order is R, G, B[, A] (OpenCV's BGR is swapped on load and on save).
struct Image {
  int width = 0, height = 0, channels = 0;
  Buffer<float> pixels;

  Image() = default;
  Image(int w, int h, int c, Device d = Device::CPU) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, d) {}
  size_t pixel_count() const { return size_t(width) * size_t(height); }
};

struct ImageSize {
  int width = 0, height = 0;
  bool operator==(const ImageSize&) const = default;
};

// Reads the image as stored (1 = grey, 3 = RGB, 4 = RGBA channels; grey+alpha becomes RGBA) on the CPU.
// 8- and 16-bit PNG/JPEG and anything else OpenCV's imgcodecs reads. Throws goris::Error naming the file.
Image read_image(const std::filesystem::path& path);

// An RGB image on `device`: grey is expanded to RGB and RGBA is composited on `background`
// (rgb * a + background * (1 - a)). alpha: when given, set to the alpha channel (one channel, on the CPU)
// or to nothing when the file has none - one decode for both.
Image load_image(const std::filesystem::path& path, Device device, glm::vec3 background = glm::vec3(0.0f),
                 std::optional<Image>* alpha = nullptr);

// A one-channel mask in [0, 1] on `device`: grey as is; colour masks use the largest of R, G, B, times the
// alpha when there is one (transparent = outside the mask).
Image load_mask(const std::filesystem::path& path, Device device = Device::CPU);

// The alpha channel in [0, 1] as a one-channel image on `device`, or nothing when the file has none.
std::optional<Image> load_alpha(const std::filesystem::path& path, Device device = Device::CPU);

// Width and height from the file header (PNG IHDR, JPEG SOF) without decoding the pixels; other formats
// fall back to a full decode. Throws goris::Error naming the file when it is missing or not an image.
ImageSize probe_image_size(const std::filesystem::path& path);

// The most pixels an image file may declare (100 megapixels: 10000x10000; a decode of it as float RGBA
// takes 1.6 GB). A PNG or JPEG whose header declares more is refused before decoding: a compressed file
// of a few hundred KB can declare gigabytes of pixels.
inline constexpr std::uint64_t kMaxImagePixels = 100000000;
// Throws goris::Error naming the file and its declared size when its PNG/JPEG header exceeds
// kMaxImagePixels (read_image calls it before decoding); other formats pass.
void check_image_header_size(const std::filesystem::path& path);

// Resamples to (width, height) on the same device: area averaging when shrinking (no aliasing),
// bilinear when enlarging. Returns a copy when the size is unchanged.
Image resize_image(const Image& image, int width, int height);

// Writes 1-, 3- or 4-channel images as PNG, 8 bits (default) or 16 bits per channel, values clamped to
// [0, 1] and rounded; through a temporary file renamed into place. The image may live on any device.
void save_png(const std::filesystem::path& path, const Image& image, bool sixteen_bit = false);

}  // namespace goris
