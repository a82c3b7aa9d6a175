#pragma once
// Stage 2 end to end (paper Sec. 3.3-3.4, S1.4-S1.6; docs/design/maths.md, Stage 2): `goris remove RUN` and
// the editor's Remove button call run_removal(). Every step reports progress and writes what it made into
// RUN/removal/ so a person can look at it:
//
//   selection        RUN/selection.json if present (goris select / the editor), else label > 0.3 closed by
//                    the hull of the selected centres, and the target's mirror twin below a planar glossy
//                    surface (intrinsic runs, or any run with glossy masks)
//                                                              -> removal/selection.json (+ .npy)
//   lighting masks   reflections of the target per training view (intrinsic runs; not with --ablate lamask)
//                                                              -> removal/lighting_masks/VIEW.png
//                                                                 (E_obj as grey: lighting_energy/VIEW.png)
//                    and, where a glossy plane was found, the target mirrored through it on the glossy
//                    surface (planar_reflection.h; inpainted, no photo loss) -> removal/reflection_masks/VIEW.png
//                    and its cast shadow (any run; not with --ablate lamask or shadows): the light is fitted
//                    to the photos' pixels on the support plane, which are relit for the fine-tune (and the
//                    reference views' renders before inpainting)
//                                                              -> removal/shadow/VIEW.png (share of light)
//   inpaint masks    pixels no view sees once the target is gone -> removal/inpaint_masks/VIEW.png
//   reference views  3 views with the largest holes, seen from different directions -> removal/reference.json
//   2D inpainting    colour, depth, normal, F0, roughness, region of each reference view (colour and depth
//                    only with --ablate material or for radiance runs)
//                                                              -> removal/inpainted/VIEW_MAP.png|.npy
//                    and the same maps but depth of every other view with a hole: its own fill, a target
//                    where no lifted point lands (view_fill_weight)  -> removal/inpainted/VIEW_fill_MAP.npy
//   3D lift          new Gaussians on the inpainted depth, never in front of the glossy plane where the
//                    hole lies on the glossy surface (plane_depth.h) (count in removal/report.json)
//   fine-tune        environment map and net frozen; photo losses outside object U lighting masks,
//                    appearance / material losses in every view's hole   -> removal/ as a run folder: config.json,
//                                                                 checkpoints/, log.csv, point_cloud.ply
//
// The result is itself a run folder (render / eval / export take RUN/removal). Cancelling (the stop flag)
// leaves the folder consistent: a rerun skips the 2D inpainting when its maps are there for the same
// inputs, and resumes the fine-tune from its last checkpoint when that was made from the same inputs
// (stage 1's model, the selection, the options: removal/made_from.json); otherwise the fine-tune starts
// over and the report says what changed.
#include <atomic>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "core/compute/device_choice.h"
#include "core/scene/mirror_twins.h"
#include "removal/lift/photo_truth_error.h"
#include "removal/lift/photo_under_reflection.h"
#include "removal/lift/surface_detail.h"

namespace goris {

enum class RemovalStep : int { Selection, LightingMasks, InpaintMasks, ReferenceViews, Inpaint2D, Lift, FineTune };
constexpr int kRemovalStepCount = 7;
const char* removal_step_name(RemovalStep step);  // "selection", "lighting masks", ...

struct RemovalOptions {
  // The 2D inpainter of colour and materials, make_inpainter() (core/inpaint/inpainter.h): harmonic, telea, ns,
  // fsr, cmd:..., dir:.... Harmonic by default: on the generalization suite it scored higher than Telea on the
  // mean and on the worst glossy scene (docs/design/deviations.md, "Appearance loss and 2D inpainting").
  std::string inpainter = "harmonic";
  std::set<std::string> ablate;     // parts switched off: removal_ablations.h
  int finetune_iterations = 0;      // 0 = 4000 at a 30K stage 1, scaled like stage 1's schedule (at least 100)
  // Every other training view's hole (its unseen pixels and the target's planar reflection) is inpainted in
  // 2D as well, and the fine-tune trains it towards that fill with this weight where no lifted reference
  // point lands (finetune_views.h; the reference views' own weight is 1). 0 = only the reference views and
  // their points supervise the hole, and novel views between them keep what stage 1 had behind the target.
  float view_fill_weight = 1.0f;
  // The material targets' weight (TrainConfig's inpaint_material_weight) is multiplied by this on a glossy
  // surface whose own colour has more detail than surface_detail.textured_above (removal/lift/surface_detail.h):
  // a smooth fill of a veined surface's base colour is a wrong target there. 1 = the same weight everywhere.
  float textured_material_weight = 0.3f;
  SurfaceDetailSettings surface_detail;
  // Inside the target's planar reflection, the dereflected photo keeps its loss where it differs from the
  // view's fill only by the surface's texture (removal/lift/photo_under_reflection.h; off with
  // ablate "texture").
  PhotoUnderReflectionSettings photo_under_reflection;
  float label_threshold = 0.3f;
  float lighting_tau = 0.1f;
  // F in the lighting-aware mask relative to the scene's F0 scale (lighting_aware_mask.h); false = the
  // paper's absolute F.
  bool lighting_relative_fresnel = true;
  // The fine-tune inside the lighting-aware mask (removal/lift/dereflect.h): true trains on the photo
  // minus stage 1's own estimate of the target's reflection; false leaves the pixels out (the paper).
  bool dereflect_lighting = true;
  // A measurement on synthetic scenes (use_true_fills, finetune_views.h): a folder of the training views
  // rendered without the target (VIEW.png, `goris synth --train-after`) that replaces every target the removal
  // made up in the fine-tune. Empty = the removal itself.
  std::string fill_truth;
  DeviceChoice device = DeviceChoice::Auto;
  // The stage-1 data set's folder when it moved after training (`goris remove --data`, train/run/run_data.h);
  // empty = RUN/config.json's. Not an input of the outputs (made_from.json): a moved data set reuses them.
  std::string data;
};

struct RemovalProgress {
  RemovalStep step = RemovalStep::Selection;
  std::size_t done = 0, total = 1;  // within the step
  std::string detail;               // e.g. the view or map being processed, loss / PSNR in the fine-tune
};

struct RemovalReport {
  std::filesystem::path out_dir;            // RUN/removal
  double seconds[kRemovalStepCount] = {};   // per step
  std::size_t gaussians_before = 0, selected = 0, added = 0, gaussians_after = 0;
  std::size_t mirror_twins = 0;  // of `selected`: the target's twin below a planar glossy surface
  std::size_t underside = 0;     // of `selected`: kept Gaussians under the target (target_underside.h)
  std::size_t lighting_pixels = 0, inpaint_pixels = 0;
  MirrorPlane glossy_plane;           // the glossy surface's plane (found = false: none)
  std::size_t reflection_pixels = 0;  // the mirrored target on the glossy surface (planar_reflection.h), all views
  std::size_t lift_onto_plane_pixels = 0;  // reference-view hole pixels moved onto the glossy plane (plane_depth.h)
  std::size_t glossy_filled_pixels = 0;  // glossy-mask pixels filled under the target (removed_glossy_masks.h)
  // The glossy surface's own detail round the hole (surface_detail.h; the reference views' median; < 0: not
  // measured) and the material targets' weight the fine-tune used.
  double surface_detail = -1;
  float material_weight = 1.0f;
  float lighting_fresnel_reference = 1.0f;  // what F was divided by in the lighting-aware masks
  std::size_t dereflected_pixels = 0;       // lighting-aware mask pixels trained on dereflected photos
  std::size_t reflection_photo_pixels = 0;  // planar-reflection pixels that kept their photo (photo_under_reflection.h)
  bool shadow_found = false;                // the target's cast shadow (removal/shadow/target_shadow.h)
  std::string shadow;                       // its light, size and strength, or why none was found
  std::size_t shadow_pixels = 0;            // training-view pixels relit by more than 5 %
  std::size_t fill_truth_pixels = 0;        // with RemovalOptions::fill_truth: training-view pixels it replaced
  PhotoTargetsTruthError truth_error;       // ... and the photos the fine-tune trains on against the truth
  std::vector<std::string> reference_views;
  int finetune_iterations = 0;
  // Why the fine-tune started over instead of resuming or reusing the earlier one in RUN/removal: which of
  // its inputs changed (core/io/made_from.h), e.g. "selection.fingerprint, options.inpainter"; "" otherwise.
  std::string finetune_restarted;
  bool cancelled = false;
};

// Runs (or resumes) stage 2 on a trained run. Throws goris::Error with the step and the problem (no
// selection, nothing to inpaint in any view, an inpainter that fails, ...).
RemovalReport run_removal(const std::filesystem::path& run_dir, const RemovalOptions& options,
                          const std::function<void(const RemovalProgress&)>& on_progress = {},
                          const std::atomic<bool>* stop = nullptr);

}  // namespace goris
