#pragma once
// The depth distortion loss (train/losses/depth_distortion.h) on the tile rasterizer: a second, light raster
// pass whose two extra channels blend each Gaussian's (m, m^2), so A, M1 and M2 come out as images; the
// loss's image gradients go back through rasterize_backward (weights: opacity, position, scale, rotation)
// and through (m, m^2) to the centres' depth. SH colour gets no gradient; the densification statistic is
// left to the photometric loss.
#include "core/compute/device.h"
#include "core/io/camera.h"
#include "core/scene/gaussian_view.h"
#include "render/raster/rasterizer.h"
#include "train/losses/depth_distortion.h"

namespace goris {

// Adds weight x dL/dparameters of the view's mean distortion into `grads` (positions, log_scales, rotations,
// opacity_logits; null ones skipped) and returns the unweighted loss. Pointers on `device`, except
// pixel_weight: [H x W] on the host, the loss's weight per pixel (null = 1).
double depth_distortion_pass(const GaussianView& gaussians, const Camera& camera, const RasterSettings& settings,
                             const DistortionDepthRange& range, float weight, const float* pixel_weight,
                             const GaussianGradView& grads, Device device);

}  // namespace goris
