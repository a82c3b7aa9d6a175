#pragma once
// The 2D-inpainted maps of a removal, kept in RUN/removal/inpainted/ so that a rerun with the same inputs
// (removal_pipeline.cpp's made_from record) skips the inpainting: each present map of a MapSet as
// STEM_MAP.npy ([H][W][C] floats), with a PNG beside it for a person to look at when asked (depth in the
// turbo colour map, normals as RGB).
#include <filesystem>
#include <string>

#include "core/inpaint/map_set.h"

namespace goris {

// Writes every present map of `maps` as DIR/STEM_MAP.npy, and DIR/STEM_MAP.png too when `previews`.
void save_inpainted_maps(const std::filesystem::path& dir, const std::string& stem, const MapSet& maps, bool previews);

// The maps DIR/STEM_MAP.npy that exist (the others stay absent). Throws goris::Error naming a file that is not
// an [H][W][C] array.
MapSet load_inpainted_maps(const std::filesystem::path& dir, const std::string& stem);
// Whether save_inpainted_maps wrote `stem`'s maps into `dir` (its colour map, which every map set has).
bool inpainted_maps_present(const std::filesystem::path& dir, const std::string& stem);

}  // namespace goris
