#pragma once
// 2D inpainting of the maps of stage 2 (RGB, depth, normal, diffuse, Fresnel F0, roughness, region)
// inside an inpainting mask, with interchangeable backends:
//
//   auto inp = make_inpainter("telea");                           // or "ns", "fsr", "cmd:...", "dir:..."
//   Image filled = inpaint_map(*inp, depth, mask, {"r_012", "depth", MapKind::Depth});
//
// inpaint_map() owns everything that depends on what a map means (map_encoding.h): depth is filled in
// inverse depth with its invalid pixels excluded as sources, normals are filled as n * 0.5 + 0.5 and
// renormalised, other ranges are stretched to [0, 1] and back. A backend (Inpainter::fill) only ever sees
// an encoded image with values in [0, 1] (colours may go above 1) and the pixels it must fill.
// Pixels outside the mask come back bit-identical to the input.
//
// Choice of backend: the harmonic fill is the removal's default for every map (RemovalOptions::inpainter):
// on depth it is exact on planes (Telea / NS leave ~20% depth errors in a 150-pixel hole on a tilted plane;
// MapSetInpaintOptions::depth_inpainter, map_set.h, keeps it for depth whatever fills the rest), and on
// colour and materials it continues the rim's gradients where Telea / NS smear the rim inwards. "cmd:" runs
// a user's learned inpainter (LaMa, SD) per map; "dir:" reads results prepared offline.
#include <memory>
#include <string>

#include "core/inpaint/mask.h"
#include "core/io/image.h"

namespace goris {

// What a map holds, which decides how it is encoded for the backends (map_encoding.h).
enum class MapKind {
  Color,   // RGB-like values in [0, 1], may exceed 1 (rendered colour, diffuse, F0): filled as is
  Unit,    // one channel in [0, 1] (roughness, region weight): filled as is, clamped to [0, 1]
  Normal,  // 3-channel direction (any length; zero = none): filled as n*0.5+0.5, renormalised
  Depth,   // one channel, camera z > 0; 0 / negative / non-finite = no surface: filled in inverse depth
  Data,    // any channels, any finite range: stretched per channel to [0.1, 0.9] and back
};
const char* map_kind_name(MapKind kind);

// Which map of which view is being filled: names files (external / precomputed backends) and messages.
struct MapInfo {
  std::string view;  // e.g. "r_012"
  std::string map;   // e.g. "rgb", "depth", "normal", "diffuse", "fresnel", "roughness", "region"
  MapKind kind = MapKind::Color;
};

class Inpainter {
 public:
  virtual ~Inpainter() = default;
  // A short description for logs, e.g. "opencv-telea (radius 3)".
  virtual std::string name() const = 0;
  // Fills `encoded` (HWC floats on the CPU, 1..4 channels, values in [0, 1] except colours that may
  // exceed 1) where `hole` is set. Returns an image of the same size and channel count; only its hole
  // pixels are used by the caller. Throws goris::Error naming the map when the backend fails.
  virtual Image fill(const Image& encoded, const Mask& hole, const MapInfo& info) const = 0;
};

// Fills `map` (any device, HWC, 1..4 channels) inside `mask` (same size; set = fill) with `inpainter`,
// encoding and decoding the map according to info.kind. Pixels outside the mask are returned exactly
// as they were. An empty mask returns a copy. Throws goris::Error for size mismatches, non-finite values
// outside the mask (depth maps: those are "no surface"), a depth map with no valid pixel outside the
// mask, or a backend failure. The result lives on the CPU.
Image inpaint_map(const Inpainter& inpainter, const Image& map, const Mask& mask, const MapInfo& info);

// Backends by name, as the command line takes them:
//   "telea" | "ns"            OpenCV cv::inpaint (Telea's fast marching / Navier-Stokes), radius 3 px;
//                             "telea:R" / "ns:R" set the radius
//   "harmonic"                Laplace fill (harmonic_inpainter.h): exact on planes in depth maps
//   "fsr" | "fsr-fast" | "fsr-best"   OpenCV contrib xphoto Frequency Selective Reconstruction
//                             (only in builds with xphoto; fsr = fsr-fast)
//   "cmd:COMMAND"             an external program per map (external_inpainter.h), default timeout 600 s
//   "dir:FOLDER"              ready-made inpainted images (precomputed_inpainter.h)
// Throws goris::Error for an unknown name (listing these) or "fsr" in a build without xphoto.
std::unique_ptr<Inpainter> make_inpainter(const std::string& spec);

}  // namespace goris
