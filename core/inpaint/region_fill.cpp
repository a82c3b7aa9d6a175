#include "core/inpaint/region_fill.h"

#include <string>

#include "core/util/error.h"

namespace goris {

Image refill_inside_region(const Inpainter& inpainter, const Image& map, const Image& filled, const Mask& hole,
                           const std::vector<float>& region, const MapInfo& info) {
  const std::size_t hw = map.pixel_count();
  if (filled.width != map.width || filled.height != map.height || filled.channels != map.channels ||
      hole.width != map.width || hole.height != map.height || region.size() != hw)
    throw Error("inpainting " + info.view + " " + info.map, "the map, its fill, the hole and the region differ in size");
  Mask unknown(map.width, map.height);  // the hole and everything outside the region
  std::size_t inside_hole = 0, sources = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    const bool in = region[p] > 0.5f;
    unknown.data[p] = hole.data[p] || !in ? 255 : 0;
    inside_hole += hole.data[p] && in;
    sources += !hole.data[p] && in;
  }
  const std::vector<float> base = filled.pixels.to_host();
  Image out(filled.width, filled.height, filled.channels);
  out.pixels = Buffer<float>(base, Device::CPU);
  if (inside_hole == 0 || sources == 0) return out;
  const std::vector<float> own = inpaint_map(inpainter, map, unknown, info).pixels.to_host();
  std::vector<float> px = base;
  const int c = map.channels;
  for (std::size_t p = 0; p < hw; ++p)
    if (hole.data[p] && region[p] > 0.5f)
      for (int k = 0; k < c; ++k) px[p * c + k] = own[p * c + k];
  out.pixels = Buffer<float>(px, Device::CPU);
  return out;
}

}  // namespace goris
