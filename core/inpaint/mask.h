#pragma once
// A binary pixel mask as stage 2 passes it around: one byte per pixel, row-major [H][W], 0 = no,
// anything else = yes (functions here write 255). For inpainting, "yes" means "fill this pixel".
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/io/image.h"

namespace goris {

struct Mask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> data;

  Mask() = default;
  Mask(int w, int h, std::uint8_t value = 0) : width(w), height(h), data(std::size_t(w) * std::size_t(h), value) {}
  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
  bool operator()(int x, int y) const { return data[std::size_t(y) * width + x] != 0; }
  void set(int x, int y, bool on) { data[std::size_t(y) * width + x] = on ? 255 : 0; }
};

// Number of set pixels.
std::size_t count_set(const Mask& mask);

// Morphological opening (erode then dilate) and closing (dilate then erode) with a square
// (2r+1) x (2r+1) structuring element; r = 0 returns the mask unchanged. Pixels outside the image
// count as unset for dilation and as set for erosion, so a mask touching the border keeps its border
// pixels through an opening.
Mask open_mask(const Mask& mask, int radius);
Mask close_mask(const Mask& mask, int radius);
Mask dilate_mask(const Mask& mask, int radius);
// The dilation radius for a soft edge at this image width: one pixel per 128 (at least 1). The removal
// grows the target's masks by it (blended silhouettes).
int soft_edge_radius(int width);

// Pixel-wise a AND b, a OR b (same sizes, else goris::Error).
Mask mask_and(const Mask& a, const Mask& b);
Mask mask_or(const Mask& a, const Mask& b);

// A one-channel image (0 or 1) for viewing/saving, and back: pixels above `threshold` are set.
// mask_from_image takes the first channel of a multi-channel image.
Image mask_to_image(const Mask& mask);
Mask mask_from_image(const Image& image, float threshold = 0.5f);

// PNG I/O: 8-bit grey, 255 = set, 0 = unset (written through a temporary file renamed into place).
// read_mask_png accepts any image read_image reads (colour: first channel), pixels > 127 are set.
void save_mask_png(const std::filesystem::path& path, const Mask& mask);
Mask read_mask_png(const std::filesystem::path& path);

}  // namespace goris
