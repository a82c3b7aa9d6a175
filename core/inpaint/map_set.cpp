#include "core/inpaint/map_set.h"

#include "core/inpaint/external_inpainter.h"
#include "core/inpaint/map_encoding.h"
#include "core/util/error.h"

namespace goris {

const std::array<MapSlot, 7>& map_slots() {
  static const std::array<MapSlot, 7> slots = {{
      {"rgb", MapKind::Color, &MapSet::rgb},
      {"depth", MapKind::Depth, &MapSet::depth},
      {"normal", MapKind::Normal, &MapSet::normal},
      {"diffuse", MapKind::Color, &MapSet::diffuse},
      {"fresnel", MapKind::Color, &MapSet::fresnel},
      {"roughness", MapKind::Unit, &MapSet::roughness},
      {"region", MapKind::Unit, &MapSet::region},
  }};
  return slots;
}

MapSet inpaint_map_set(const Inpainter& inpainter, const MapSet& maps, const Mask& mask, const std::string& view,
                       const MapSetInpaintOptions& options) {
  MapSet out;
  for (const MapSlot& s : map_slots()) {
    const Image& in = maps.*s.member;
    if (in.pixel_count() == 0) continue;
    if (options.on_map) options.on_map(s.name);
    const Inpainter& which = s.kind == MapKind::Depth && options.depth_inpainter ? *options.depth_inpainter : inpainter;
    out.*s.member = inpaint_map(which, in, mask, MapInfo{view, s.name, s.kind});
  }
  return out;
}

void write_inpainting_inputs(const std::filesystem::path& dir, const MapSet& maps, const Mask& mask,
                             const std::string& view) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir.string(), "cannot create the folder: " + ec.message());
  for (const MapSlot& s : map_slots()) {
    const Image& in = maps.*s.member;
    if (in.pixel_count() == 0) continue;
    const MapInfo info{view, s.name, s.kind};
    const EncodedMap enc = encode_map(in, mask, info);
    const std::string stem = file_safe(view) + "_" + s.name;
    save_encoded_png(dir / (stem + ".png"), enc.image, s.kind);
    save_mask_png(dir / (stem + "_mask.png"), enc.hole);
  }
}

}  // namespace goris
