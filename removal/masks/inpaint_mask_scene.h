#pragma once
// Splitting a scene into what stays and what is removed (stage 2): compacted copies of a GaussianModel.
#include <cstdint>
#include <vector>

#include "core/scene/gaussians.h"

namespace goris {

// The Gaussians i with take[i] != 0, in their order, on the model's device: values, gradients, Adam
// moments and the 3D filter are copied, SH degrees kept. Throws goris::Error when take.size() differs
// from model.count().
GaussianModel subset_model(const GaussianModel& model, const std::vector<std::uint8_t>& take);

struct SplitScene {
  GaussianModel kept;    // removed[i] == 0: the scene after removal
  GaussianModel target;  // removed[i] != 0: the object alone
};
// Both halves of `model` for a per-Gaussian `removed` mask (1 = target).
SplitScene split_removed(const GaussianModel& model, const std::vector<std::uint8_t>& removed);

}  // namespace goris
