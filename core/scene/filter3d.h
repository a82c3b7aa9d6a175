#pragma once
// Mip-Splatting's 3D smoothing filter: every Gaussian gets a minimum world-space variance matching the
// highest sampling rate any training camera sees it at, so it can never shrink below what the training
// images can resolve (no high-frequency artefacts when zooming in).
#include <vector>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"

namespace goris {

// Sets model.filter3d_var[i] = 0.2 / rate_i^2 with rate_i = max over cameras seeing Gaussian i of
// fx / z (pixels per world unit at its depth z), exactly Mip-Splatting's (depth / focal * sqrt(0.2))^2.
// "Seeing": z > 0.2 and the projected centre within 15% of the image size outside its borders.
// Gaussians no camera sees take the lowest rate among those seen. Cameras at the training resolution.
void compute_filter3d(GaussianModel& model, const std::vector<Camera>& cameras);

}  // namespace goris
