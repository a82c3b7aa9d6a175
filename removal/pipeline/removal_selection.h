#pragma once
// Step 1 of `goris remove`: what goes. The run's selection (RUN/selection.json, else the intrinsic model's
// learned labels), the glossy plane, the target's mirror twin below it (core/scene/mirror_twins.h) and what
// stands under the target on the glossy surface (removal/selection/target_underside.h).
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"
#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"
#include "removal/pipeline/removal_pipeline.h"
#include "removal/selection/selection_file.h"
#include "train/loop/trainer.h"

namespace goris {

struct RemovalSelection {
  SelectionMask selected;  // everything that goes
  SelectionMask target;    // the target alone: the shadow's occluder, the planar reflection's source
  SelectionMask twins;     // of `selected`: the target's mirror twin
  // What the shadow fit keeps out of its support surface: `selected` without the target's underside, which
  // stands on the surface at the target's foot (with it left out, the fit chose another light on the suite's
  // worst scene: docs/design/deviations.md, "The target's underside").
  SelectionMask shadow_excluded;
  MirrorPlane glossy_plane;  // found = false: none (or not looked for: twins and reflection both ablated)
  std::size_t mirror_twins = 0, underside = 0;  // of `selected`
  SelectionRecord record;   // how the selection was made, with the twin and underside counts
  std::string note;         // for the step's progress line, after "N of M Gaussians"
};

// Throws goris::Error ("goris remove (selection): ...") when nothing or more than half the model is selected.
RemovalSelection select_for_removal(const std::filesystem::path& run_dir, const GaussianModel& model,
                                    const RemovalOptions& options, bool intrinsic, bool glossy_masks,
                                    const std::vector<Camera>& cameras, const std::vector<TrainView>& views);

}  // namespace goris
