#pragma once
// The tile rasterizer (render/raster/rasterizer.h) behind the trainer's DifferentiableRenderer interface.
#include "render/raster/rasterizer.h"
#include "train/config/train_config.h"
#include "train/loop/differentiable_renderer.h"

namespace goris {

// The trainer's view of a rasterizer output (colour = base colour = the rasterized SH colour).
RenderedImages rendered_from_raster(const RasterOutput& raster);

// Back-propagates gradients on the extra channels into grads.extras alone (a second backward pass with
// every other gradient left out): ImageGradients::extras_detached. No-op when either is null.
void backward_detached_extras(const GaussianView& gaussians, const RasterState& state, const float* d_extras,
                              const GaussianGradView& grads);

class RasterRenderer final : public DifferentiableRenderer {
 public:
  RasterRenderer(const RasterSettings& settings, Device device) : settings_(settings), device_(device) {}
  // Settings of a training configuration: Mip-Splatting's 2D filter (or 3DGS's dilation), its background.
  static RasterSettings settings_for(const TrainConfig& config);
  Device device() const override { return device_; }
  RenderedImages forward(const GaussianView& gaussians, const Camera& camera) override;
  void backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) override;
  double depth_distortion(const GaussianView& gaussians, const Camera& camera, const DistortionDepthRange& range,
                          float weight, const float* pixel_weight, const GaussianGradView& grads) override;
  // The last forward pass (G-buffer and state), e.g. for the extra channels.
  const RasterOutput& last() const { return last_; }

 private:
  RasterSettings settings_;
  Device device_;
  RasterOutput last_;
};

}  // namespace goris
