#include "removal/masks/removed_glossy_masks.h"

#include <string>

#include "core/inpaint/harmonic_inpainter.h"
#include "core/util/error.h"

namespace goris {

std::vector<float> removed_glossy_mask(const TrainView& v, const InpaintMaskView& hole_view, std::size_t* filled) {
  if (filled) *filled = 0;
  if (v.glossy_mask.empty()) return {};
  const int w = v.camera.width, h = v.camera.height;
  const Mask& covered = hole_view.covered;
  if (covered.width != w || covered.height != h || v.glossy_mask.size() != std::size_t(w) * std::size_t(h))
    throw Error("removal: the glossy mask or the target's coverage of training view " + v.name +
                " does not have the view's size " + std::to_string(w) + "x" + std::to_string(h));
  std::vector<float> mask = v.glossy_mask;
  const Mask hole = dilate_mask(covered, soft_edge_radius(w));
  const std::size_t n = count_set(hole);
  if (n == 0 || n == hole.pixel_count()) return mask;  // nothing to fill, or nothing to fill from
  const HarmonicInpainter harmonic;
  Image map(w, h, 1);
  for (std::size_t p = 0; p < mask.size(); ++p) map.pixels[p] = mask[p];
  const std::vector<float> values = inpaint_map(harmonic, map, hole, {v.name, "glossy", MapKind::Unit}).pixels.to_host();
  for (std::size_t p = 0; p < values.size(); ++p)
    if (hole.data[p]) mask[p] = values[p];
  if (filled) *filled = n;
  return mask;
}

std::size_t fill_removed_glossy_masks(std::vector<TrainView>& views, const std::vector<InpaintMaskView>& holes) {
  if (holes.size() != views.size())
    throw Error("removal: " + std::to_string(holes.size()) + " inpainting masks for " + std::to_string(views.size()) +
                " training views");
  std::size_t filled = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    std::size_t n = 0;
    std::vector<float> m = removed_glossy_mask(views[i], holes[i], &n);
    if (!m.empty()) views[i].glossy_mask = std::move(m);
    filled += n;
  }
  return filled;
}

}  // namespace goris
