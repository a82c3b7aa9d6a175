#pragma once
// What the trainer needs from a differentiable renderer. core/ never links render/ (the dependency runs
// render -> core), so the trainer talks to this interface and render/ implements it (the rasterizer:
// render/train/raster_renderer.h).
#include <cstdint>

#include "core/compute/device.h"
#include "core/io/camera.h"
#include "core/scene/gaussian_view.h"

namespace goris {

// Planar images ([C][H][W], row-major per channel) on the renderer's device, valid until the next forward.
struct RenderedImages {
  int width = 0, height = 0;
  const float* color = nullptr;         // [3][H][W], background included
  const float* alpha = nullptr;         // [H][W]
  const float* depth = nullptr;         // [H][W] alpha-weighted camera z (not divided by alpha)
  const float* median_depth = nullptr;  // [H][W]
  const float* normal = nullptr;        // [3][H][W] camera space, facing the camera, not normalised
  const std::int32_t* radii = nullptr;  // [N] screen radius per Gaussian, 0 = not visible
};

// dL/d(image) for the last forward; null = zero.
struct ImageGradients {
  const float* color = nullptr;
  const float* alpha = nullptr;
  const float* depth = nullptr;
  const float* median_depth = nullptr;
  const float* normal = nullptr;
};

class DifferentiableRenderer {
 public:
  virtual ~DifferentiableRenderer() = default;
  virtual Device device() const = 0;
  virtual RenderedImages forward(const GaussianView& gaussians, const Camera& camera) = 0;
  // Adds dL/dparameters of the last forward's Gaussians into `grads` (grads.mean2d_grad_norm included).
  virtual void backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) = 0;
};

}  // namespace goris
