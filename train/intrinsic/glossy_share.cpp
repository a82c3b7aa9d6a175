#include "train/intrinsic/glossy_share.h"

#include <string>

#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"

namespace goris {

void add_glossy_share(const std::vector<float>& colour, const std::vector<float>& sh_colour,
                      const std::vector<float>& glossy_mask, GlossyShare& share) {
  const std::size_t hw = glossy_mask.size();
  if (colour.size() != 3 * hw || sh_colour.size() != 3 * hw)
    throw Error("glossy share: " + std::to_string(colour.size()) + " colour and " + std::to_string(sh_colour.size()) +
                " SH colour values for a mask of " + std::to_string(hw) + " pixels (3 per pixel expected)");
  std::size_t pixels = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    if (!(glossy_mask[p] >= 0.5f)) continue;
    ++pixels;
    for (std::size_t c = 0; c < 3; ++c) {
      share.colour_sum += colour[c * hw + p];
      share.glossy_sum += colour[c * hw + p] - sh_colour[c * hw + p];
    }
  }
  share.pixels += pixels;
  if (pixels > 0) ++share.views;
}

GlossyShare measure_glossy_share(IntrinsicRenderer& renderer, const GaussianView& gaussians,
                                 const std::vector<TrainView>& views) {
  GlossyShare share;
  for (const TrainView& v : views) {
    if (v.glossy_mask.empty()) continue;
    const IntrinsicMaps m = renderer.render_maps(gaussians, v.camera);
    add_glossy_share(m.color, m.sh_color, v.glossy_mask, share);
  }
  return share;
}

}  // namespace goris
