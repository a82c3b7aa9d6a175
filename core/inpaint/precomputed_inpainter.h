#pragma once
// Ready-made inpainted images (the command line's --inpainted DIR): instead of filling a map, read
// DIR/VIEW_MAP.png, e.g. DIR/r_012_rgb.png, DIR/r_012_depth.png, DIR/r_012_roughness.png (names made
// file-safe as in external_inpainter.h: characters other than letters, digits, '.', '-', '_' become '_').
// MAP is one of rgb, depth, normal, diffuse, fresnel, roughness, region.
//
// The images must use the encoding of map_encoding.h, i.e. be what an inpainting program returns for
// the files write_inpainting_inputs() (map_set.h) writes: colour / unit maps as they are, normals as
// n*0.5+0.5, depth as the normalised inverse depth of that exact input. Size must match the view; any
// bit depth; channel rules as for external programs. Pixels outside the mask are never taken from the
// file. A missing file uses the fallback inpainter when one is given, and is an error otherwise.
#include <filesystem>
#include <memory>

#include "core/inpaint/inpainter.h"

namespace goris {

// DIR/VIEW_MAP.png for a map.
std::filesystem::path inpainted_file(const std::filesystem::path& dir, const MapInfo& info);

class PrecomputedInpainter final : public Inpainter {
 public:
  // Throws goris::Error when `dir` is not a folder.
  explicit PrecomputedInpainter(std::filesystem::path dir, std::shared_ptr<const Inpainter> fallback = nullptr);
  std::string name() const override;
  Image fill(const Image& encoded, const Mask& hole, const MapInfo& info) const override;

 private:
  std::filesystem::path dir_;
  std::shared_ptr<const Inpainter> fallback_;
};

}  // namespace goris
