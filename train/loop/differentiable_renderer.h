#pragma once
// What the trainer needs from a differentiable renderer. core/ never links render/ (the dependency runs
// render -> core), so the trainer talks to this interface and render/ implements it (the rasterizer:
// train/radiance/raster_renderer.h).
#include <cstdint>
#include <string>
#include <vector>

#include "core/compute/device.h"
#include "core/io/camera.h"
#include "core/scene/gaussian_view.h"
#include "train/losses/depth_distortion.h"

namespace goris {

// Planar images ([C][H][W], row-major per channel) on the renderer's device, valid until the next forward.
struct RenderedImages {
  int width = 0, height = 0;
  const float* color = nullptr;         // [3][H][W], background included
  const float* base_color = nullptr;    // [3][H][W] D, the rasterized SH colour (== color for radiance)
  const float* alpha = nullptr;         // [H][W]
  const float* depth = nullptr;         // [H][W] alpha-weighted camera z (not divided by alpha)
  const float* median_depth = nullptr;  // [H][W]
  const float* normal = nullptr;        // [3][H][W] camera space, facing the camera, not normalised
  const std::int32_t* radii = nullptr;  // [N] screen radius per Gaussian, 0 = not visible
  const float* extras = nullptr;        // [n_extras][H][W] blended extra channels (intrinsic renderers)
  int n_extras = 0;
};

// dL/d(image) for the last forward; null = zero.
struct ImageGradients {
  const float* color = nullptr;
  const float* alpha = nullptr;
  const float* depth = nullptr;
  const float* median_depth = nullptr;
  const float* normal = nullptr;
  const float* extras = nullptr;  // [n_extras][H][W]
  const float* base_color = nullptr;  // [3][H][W] dL/dD (only from renderers whose base_color != color)
  // Gradients on the extra channels that train the per-Gaussian extras only, not the geometry that
  // blends them (the object label: a mask must not make Gaussians transparent). [n_extras][H][W]
  const float* extras_detached = nullptr;
};

class DifferentiableRenderer {
 public:
  virtual ~DifferentiableRenderer() = default;
  virtual Device device() const = 0;
  virtual RenderedImages forward(const GaussianView& gaussians, const Camera& camera) = 0;
  // Adds dL/dparameters of the last forward's Gaussians into `grads` (grads.mean2d_grad_norm included).
  virtual void backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) = 0;

  // The depth distortion loss of the Gaussians seen by `camera` (a pass of its own, independent of the last
  // forward), weighted per pixel by pixel_weight ([H x W] on the host; null = 1): adds weight x
  // dL/dparameters into `grads` and returns the unweighted loss; 0 where unsupported.
  virtual double depth_distortion(const GaussianView& /*gaussians*/, const Camera& /*camera*/,
                                  const DistortionDepthRange& /*range*/, float /*weight*/,
                                  const float* /*pixel_weight*/, const GaussianGradView& /*grads*/) {
    return 0.0;
  }
  // Whether forward() wants the Gaussians' extra channels (model.view(true)) and returns them.
  virtual bool wants_extras() const { return false; }
  // Told the iteration about to run before its forward pass (e.g. to switch from the radiance warm-up to
  // shading).
  virtual void begin_iteration(int /*iteration*/) {}
  // Per-Gaussian weights of their colour in traced rays, overriding the renderer's own rule (empty = its
  // own), or with or_own the larger of the two. Renderers that trace nothing ignore them.
  virtual void set_emit_weights(std::vector<float> /*weights*/, bool /*or_own*/) {}
  // Parameters the renderer owns (environment map, roughness net): one optimiser step after backward(),
  // with the renderer's own schedule; throws goris::Error naming the parameters when they turn non-finite.
  virtual void step_own_parameters(int /*iteration*/) {}
  // Those parameters with their optimiser state, as bytes stored beside each checkpoint (empty = none).
  virtual std::string save_own_state() const { return {}; }
  // Restores save_own_state()'s bytes; `source` names the file in errors.
  virtual void load_own_state(const std::string& /*bytes*/, const std::string& /*source*/) {}
};

}  // namespace goris
