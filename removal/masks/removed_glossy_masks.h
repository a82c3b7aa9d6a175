#pragma once
// The glossy masks of the scene without the target, for the fine-tune and every later render of the
// removal. The photos' masks mark the target's pixels as not glossy (0), but after the removal the lifted,
// inpainted surface is seen there. With intrinsic_emit = mask | max a Gaussian emits by its mean mask vote
// (train/loop/emit_weights.h), so the Gaussians the lift places on the table where the target stood would
// take the target's vote and emit into the table's own traced rays. The region loss and the smoothness
// terms, which are restricted to the glossy mask, would also skip that surface. (A ghost once seen after
// removal with emit = mask was suspected to come from the votes; filling the masks did not change it, so
// that ghost has another cause: docs/lab/bench/NOTES.md, 2026-11-22, "emit = mask after removal".)
//
// Under the target's (and its mirror twin's) coverage, dilated by soft_edge_radius for its soft edges, each
// view's mask is filled from the surrounding pixels with the harmonic fill (a Unit map: exact on linear
// ramps, so a hole inside the table fills with 1 and a hole on the table's border blends to its outside).
#include <cstddef>
#include <vector>

#include "removal/masks/inpaint_mask.h"
#include "train/loop/trainer.h"

namespace goris {

// One view's mask filled under hole_view.covered (empty when the view has no glossy mask); `filled`, when
// given, receives the number of pixels filled.
std::vector<float> removed_glossy_mask(const TrainView& view, const InpaintMaskView& hole_view,
                                       std::size_t* filled = nullptr);

// Fills views[i].glossy_mask under holes[i].covered (views without a glossy mask are left alone; a size
// mismatch throws goris::Error naming the view). Returns the number of pixels filled over all views.
std::size_t fill_removed_glossy_masks(std::vector<TrainView>& views, const std::vector<InpaintMaskView>& holes);

}  // namespace goris
