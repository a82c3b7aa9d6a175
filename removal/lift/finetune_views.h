#pragma once
// The training views of the stage-2 fine-tune (paper Sec. 3.4 and S1.4-S1.5; docs/design/maths.md, Stage 2):
//  - every view keeps its photo, but the photo losses only count outside its `exclude` mask (object mask,
//    and the lighting-aware mask under the paper's rule; by default the photo is dereflected there instead,
//    dereflect.h): TrainView::loss_weight = 0 there;
//  - reference views get inpainting targets on their hole: the inpainted colour as an appearance target
//    where the inpainted region map says rough (M > 0.5), the inpainted materials (D, F0, roughness,
//    normal) as targets where it says glossy;
//  - the other views get the reference points projected into them (nearest point per pixel, kept only
//    where the view's photo loss is off and the removed scene's own surface is not in front: depth test
//    with a relative tolerance), as sparse targets of the same two kinds;
//  - where a view has a 2D fill of its own hole (`fill`), the hole pixels that no reference point reached
//    take that fill as targets of the same two kinds, weighted by its `weight`: without it the fine-tune
//    sees nothing there, and whatever stage 1 kept behind the target (a radiance model's mirror twin seen
//    through a glossy surface) stays in the novel views between the reference views.
#include <vector>

#include "core/inpaint/map_set.h"
#include "core/inpaint/mask.h"
#include "removal/lift/lift.h"
#include "removal/lift/photo_truth_error.h"
#include "train/loop/trainer.h"

namespace goris {

struct FinetuneViewSettings {
  float depth_tolerance = 0.05f;  // relative: a point is hidden when the removed surface is this much in front
  float rough_threshold = 0.5f;   // inpainted region M above this = rough (appearance target)
};

// What each training view contributes, in the same order as `views`.
struct FinetuneViewInputs {
  const Mask* exclude = nullptr;       // object mask [U lighting-aware mask] (255 = no photo loss)
  const Image* removed_depth = nullptr;  // removed scene's surface depth (0 = none), for the depth test
  int reference = -1;                  // index into `references` when this is a reference view
  int fill = -1;                       // index into `references` of this view's own 2D fill (other views)
};

struct ReferenceTargets {
  const Mask* hole = nullptr;   // the inpainting mask
  const MapSet* maps = nullptr; // inpainted: rgb required; region, fresnel, roughness, normal optional
  float weight = 1.0f;          // of its appearance and material targets
};

struct FinetuneViewStats {
  std::size_t excluded_pixels = 0, appearance_pixels = 0, material_pixels = 0, projected_points = 0;
  std::size_t filled_pixels = 0;  // of the appearance and material pixels: from a view's own fill
};

// Fills loss_weight and inpaint of every view (replacing what was there). `points` are the lift's reference
// points (world positions; colour; materials; world normals). Throws goris::Error for sizes that differ.
FinetuneViewStats prepare_finetune_views(std::vector<TrainView>& views, const std::vector<FinetuneViewInputs>& inputs,
                                         const std::vector<ReferenceTargets>& references,
                                         const ReferencePoints& points, const FinetuneViewSettings& settings = {});

// A measurement, not a removal: on a synthetic scene whose training views were also rendered without the
// target (`goris synth --train-after`), every pixel of a view that the removal made up - its photo loss off
// (the target's grown silhouette, its planar reflection) or an inpainting target - takes that true image
// under the photo loss instead, and the view's inpainting targets go. What the removal then scores is what
// perfect fills would give it on the same stage 1, masks, lift and fine-tune. `truth[i]` is planar RGB
// [3][H][W] of views[i]; returns the pixels replaced. Throws goris::Error (the view's name) for a size
// that differs.
std::size_t use_true_fills(std::vector<TrainView>& views, const std::vector<std::vector<float>>& truth);

// The same measurement's other half: how much of the target the photos the fine-tune trains on still carry,
// against the true images, before and after the removal changed them (dereflected inside the lighting-aware
// mask, relit where the target's shadow was found). Sums over every view of the mean-RGB |x - truth| per
// pixel; `photos[i]` and `truth[i]` are planar RGB [3][H][W] of views[i], the views as prepared for the
// fine-tune (call it before use_true_fills). Throws goris::Error (the view's name) for a size that differs.
PhotoTargetsTruthError photo_targets_against_truth(const std::vector<TrainView>& views,
                                                   const std::vector<std::vector<float>>& photos,
                                                   const std::vector<std::vector<float>>& truth);

}  // namespace goris
