#pragma once
// Which Gaussians emit into traced rays, from the data instead of the learned region weight
// (intrinsic_emit = mask): the paper lets only rough-region Gaussians emit, and with its one-sided region
// loss M drifts to ~0 on the objects too, so the table's traced reflections of them come out black and the
// radiance warm-up's mirror world keeps them. Here a Gaussian emits 1 - (its mean glossy-mask value over
// the training views its centre projects into): objects emit, the glossy surface (and the mirror world seen
// through it) does not.
#include <cstddef>
#include <vector>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"
#include "train/loop/trainer.h"

namespace goris {

// A training camera and its glossy mask (H x W, 1 = glossy), all the weights depend on besides the centres.
struct GlossyMaskView {
  Camera camera;
  std::vector<float> mask;
};

// One weight per Gaussian in [0, 1]; 1 where no view with a glossy mask sees the centre. `positions` is
// [count][3] on the host.
std::vector<float> glossy_mask_emit_weights(const std::vector<float>& positions, const std::vector<GlossyMaskView>& views);
// The same for a model and the trainer's views (views without a glossy mask are skipped).
std::vector<float> glossy_mask_emit_weights(const GaussianModel& model, const std::vector<TrainView>& views);

}  // namespace goris
