#include <string>
#include <vector>

#include "core/inpaint/inpainter.h"
#include "core/inpaint/map_encoding.h"
#include "core/util/error.h"

namespace goris {

Image inpaint_map(const Inpainter& inpainter, const Image& map, const Mask& mask, const MapInfo& info) {
  const EncodedMap enc = encode_map(map, mask, info);  // validates sizes, channels and values
  const std::vector<float> original = map.pixels.to_host();
  Image result(map.width, map.height, map.channels, Device::CPU);
  result.pixels.upload(original.data(), original.size());
  if (count_set(mask) == 0) return result;

  const Image filled = inpainter.fill(enc.image, enc.hole, info);
  if (filled.width != map.width || filled.height != map.height || filled.channels != map.channels)
    throw Error(map_label(info), inpainter.name() + " returned a " + std::to_string(filled.width) + "x" +
                                     std::to_string(filled.height) + "x" + std::to_string(filled.channels) +
                                     " image for a " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                                     "x" + std::to_string(map.channels) + " map");
  const Image decoded = decode_map(filled, enc);
  const int C = map.channels;
  for (std::size_t p = 0; p < map.pixel_count(); ++p)
    if (mask.data[p])
      for (int c = 0; c < C; ++c) result.pixels[p * C + c] = decoded.pixels[p * C + c];
  return result;
}

}  // namespace goris
