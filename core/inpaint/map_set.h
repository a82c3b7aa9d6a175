#pragma once
// The maps of one view that stage 2 inpaints together (the paper's Sec. 3.3 / S1.4: colour and the
// material maps under the same mask, plus depth for the 3D lift and the region map to tell glossy from
// rough inside the hole). An empty Image means "this map is absent" and is skipped.
#include <array>
#include <filesystem>
#include <functional>
#include <string>

#include "core/inpaint/inpainter.h"

namespace goris {

struct MapSet {
  Image rgb;        // 3 channels: colour
  Image depth;      // 1: camera-space z (OpenCV camera, z forward), 0 = no surface
  Image normal;     // 3: camera-space normal, unit or zero (= none)
  Image diffuse;    // 3: diffuse colour D
  Image fresnel;    // 3: Fresnel F0
  Image roughness;  // 1
  Image region;     // 1: region weight M (1 = rough / Lambertian, 0 = glossy)
};

// Every map of a MapSet with its file name part and kind, in this order: rgb, depth, normal, diffuse,
// fresnel, roughness, region.
struct MapSlot {
  const char* name;
  MapKind kind;
  Image MapSet::*member;
};
const std::array<MapSlot, 7>& map_slots();

struct MapSetInpaintOptions {
  // Fills the depth map instead of the main inpainter when set; a HarmonicInpainter is the recommended
  // choice (planes stay planes, which is what the lift back-projects).
  const Inpainter* depth_inpainter = nullptr;
  std::function<void(const std::string& map)> on_map;  // told each map's name before it is filled
};

// Fills every present map inside `mask` with inpaint_map(). Absent maps stay absent.
MapSet inpaint_map_set(const Inpainter& inpainter, const MapSet& maps, const Mask& mask, const std::string& view,
                       const MapSetInpaintOptions& options = {});

// Writes, for each present map, DIR/VIEW_MAP.png and DIR/VIEW_MAP_mask.png exactly as the external
// inpainter hands them to a program (encoding and bit depths in external_inpainter.h). Running a tool
// on them and saving its results as OUT/VIEW_MAP.png gives a folder PrecomputedInpainter (--inpainted)
// reads. Files are written through temporary files renamed into place.
void write_inpainting_inputs(const std::filesystem::path& dir, const MapSet& maps, const Mask& mask,
                             const std::string& view);

}  // namespace goris
