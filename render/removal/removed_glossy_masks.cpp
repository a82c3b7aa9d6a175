#include "render/removal/removed_glossy_masks.h"

#include <string>

#include "core/inpaint/harmonic_inpainter.h"
#include "core/util/error.h"

namespace goris {

std::size_t fill_removed_glossy_masks(std::vector<TrainView>& views, const std::vector<InpaintMaskView>& holes) {
  if (holes.size() != views.size())
    throw Error("removal: " + std::to_string(holes.size()) + " inpainting masks for " + std::to_string(views.size()) +
                " training views");
  const HarmonicInpainter harmonic;
  std::size_t filled = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    TrainView& v = views[i];
    if (v.glossy_mask.empty()) continue;
    const int w = v.camera.width, h = v.camera.height;
    const Mask& covered = holes[i].covered;
    if (covered.width != w || covered.height != h || v.glossy_mask.size() != std::size_t(w) * std::size_t(h))
      throw Error("removal: the glossy mask or the target's coverage of training view " + v.name +
                  " does not have the view's size " + std::to_string(w) + "x" + std::to_string(h));
    const Mask hole = dilate_mask(covered, soft_edge_radius(w));
    const std::size_t n = count_set(hole);
    if (n == 0) continue;
    if (n == hole.pixel_count()) continue;  // nothing to fill from: keep the photo's mask
    Image map(w, h, 1);
    for (std::size_t p = 0; p < v.glossy_mask.size(); ++p) map.pixels[p] = v.glossy_mask[p];
    const Image out = inpaint_map(harmonic, map, hole, {v.name, "glossy", MapKind::Unit});
    const std::vector<float> values = out.pixels.to_host();
    for (std::size_t p = 0; p < values.size(); ++p)
      if (hole.data[p]) v.glossy_mask[p] = values[p];
    filled += n;
  }
  return filled;
}

}  // namespace goris
