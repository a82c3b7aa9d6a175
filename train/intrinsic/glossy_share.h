#pragma once
// Where an intrinsic model keeps the glossy surface's reflections: the share of the surface's rendered colour
// that the traced glossy term carries. The shading is C = D + (1 - M) G (docs/design/maths.md, Shading); over
// the training views' glossy pixels (glossy mask >= 0.5) the share is sum (C - D) / sum C over the pixels and
// RGB. The paper's decomposition puts the reflections in G, so that removing the target's Gaussians removes
// its reflection too; a share near 0 says they live in D instead (a mirror world behind the surface, or
// view-dependent SH colour), where only the removal's reflection mask and fills take the target's away.
#include <cstddef>
#include <optional>
#include <vector>

#include "core/scene/gaussians.h"
#include "train/loop/trainer.h"

namespace goris {

class IntrinsicRenderer;

struct GlossyShare {
  std::size_t views = 0, pixels = 0;  // views with a glossy pixel, glossy pixels over them
  double colour_sum = 0, glossy_sum = 0;  // sum C and sum (C - D) over those pixels and RGB
  // sum (C - D) / sum C; nullopt without glossy pixels or when they render black.
  std::optional<double> share() const {
    return pixels > 0 && colour_sum > 0 ? std::optional<double>(glossy_sum / colour_sum) : std::nullopt;
  }
};

// Adds one view: `colour` and `sh_colour` [3][H][W] planar, `glossy_mask` [H][W]. Throws goris::Error when
// the sizes do not agree.
void add_glossy_share(const std::vector<float>& colour, const std::vector<float>& sh_colour,
                      const std::vector<float>& glossy_mask, GlossyShare& share);

// Renders every view that has a glossy mask with `renderer` (IntrinsicRenderer::render_maps) and adds it.
GlossyShare measure_glossy_share(IntrinsicRenderer& renderer, const GaussianView& gaussians,
                                 const std::vector<TrainView>& views);

}  // namespace goris
