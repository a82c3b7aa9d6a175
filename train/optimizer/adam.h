#pragma once
// Adam over the scene model's parameter groups (bias-corrected, eps 1e-15 as in 3DGS), on the model's
// device. Each group keeps its own step count, so a group that starts training late (the materials after
// the radiance warm-up) gets its own bias correction.
#include <array>

#include "train/optimizer/param_groups.h"

namespace goris {

class GaussianAdam {
 public:
  float beta1 = 0.9f, beta2 = 0.999f, eps = 1e-15f;
  std::array<int, kGroupCount> steps{};  // updates done so far, per group

  // One update of `group` with learning rate `lr` from the model's current gradients. col_end > 0 stops
  // at that column of the tensor (the SH coefficients above the active degree have no gradient and zero
  // moments, so skipping them changes nothing).
  void step(GaussianModel& model, ParamGroup group, float lr, int col_end = 0);
};

// Zeroes the Adam moments of one group (after an opacity reset, as 3DGS does).
void reset_moments(GaussianModel& model, ParamGroup group);

}  // namespace goris
