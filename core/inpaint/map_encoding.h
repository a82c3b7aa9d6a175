#pragma once
// How each kind of map is turned into what an inpainting backend fills, and back. Every backend sees
// values in [0, 1] (colours may exceed 1), so the same encoding serves OpenCV, FSR, external programs
// (which receive it as PNG) and ready-made inpainted images (which must use it):
//
//   Color   as is (decoded values clamped at >= 0)
//   Unit    as is (decoded values clamped to [0, 1])
//   Normal  n / |n| * 0.5 + 0.5 (zero-length normals encode as 0.5); decoded as normalize(2 e - 1), with
//           (0, 0, -1) (facing an OpenCV camera) where the fill has no direction
//   Depth   e = 0.1 + 0.8 (1/z - lo) / (hi - lo), lo / hi = min / max of 1/z over the valid pixels outside
//           the mask (near = bright); invalid pixels (z <= 0 or non-finite) encode as 0 and are added to
//           the hole, so no fill is blended with "no surface"; decoded z = 1/inverse depth, 0 where the
//           inverse depth is <= 0. Inverse depth is affine in the pixel coordinates on a plane, so
//           smooth fills reproduce planes.
//   Data    per channel e = 0.1 + 0.8 (v - lo) / (hi - lo) over the pixels outside the mask
// A constant channel (hi == lo) is widened so that it encodes to 0.5. The 0.1 / 0.9 margins leave a
// backend room to extrapolate a little beyond the known range.
#include <filesystem>
#include <vector>

#include "core/inpaint/inpainter.h"

namespace goris {

struct EncodedMap {
  Image image;  // HWC on the CPU, the backend's input
  Mask hole;    // what the backend must fill: the mask, plus invalid pixels of a depth map
  MapKind kind = MapKind::Color;
  std::vector<float> lo, hi;  // per channel (Depth: one, in inverse depth; Data: each); empty otherwise
};

// Encodes `map` for filling inside `mask`. Throws goris::Error (naming info.view / info.map) for a size
// mismatch, a channel count the kind cannot have (Normal: 3, Depth / Unit: 1, any: 1..4), non-finite
// values outside the mask (except depth), or a depth map with no valid pixel outside the mask.
EncodedMap encode_map(const Image& map, const Mask& mask, const MapInfo& info);

// The filled encoded image back in the map's units (every pixel decoded; the caller keeps the originals
// outside the mask).
Image decode_map(const Image& filled, const EncodedMap& encoding);

// An image a program returned (or a file provided) with the channel count of `encoded`: a grey result
// fills every channel, a colour result for a one-channel map is averaged over R, G, B, extra channels
// (alpha) are dropped, and missing ones (an RGB result for an RGBA map) are taken from `encoded`.
Image adapt_channels(const Image& got, const Image& encoded);

// Writes an encoded map as PNG (through a temporary file): 16 bits per channel for Depth and Data maps,
// 8 bits otherwise; grey for 1 channel, RGB for 3, RGBA for 4, and a 2-channel map with a zero blue.
void save_encoded_png(const std::filesystem::path& path, const Image& encoded, MapKind kind);

// "VIEW/MAP" for messages.
std::string map_label(const MapInfo& info);

}  // namespace goris
