#include "train/radiance/raster_renderer.h"

#include "train/radiance/depth_distortion_pass.h"

namespace goris {

RasterSettings RasterRenderer::settings_for(const TrainConfig& config) {
  RasterSettings s =
      config.anti_aliasing.filter_2d ? RasterSettings::mip_splatting() : RasterSettings::classic_3dgs();
  s.background = config.input.background;
  return s;
}

RenderedImages rendered_from_raster(const RasterOutput& raster) {
  const GBuffer& g = raster.gbuffer;
  RenderedImages r;
  r.width = g.width;
  r.height = g.height;
  r.color = g.color.data();
  r.base_color = r.color;
  r.alpha = g.alpha.data();
  r.depth = g.depth.data();
  r.median_depth = g.median_depth.data();
  r.normal = g.normal.data();
  r.radii = raster.state.radii.data();
  r.extras = g.n_extras > 0 ? g.extras.data() : nullptr;
  r.n_extras = g.n_extras;
  return r;
}

RenderedImages RasterRenderer::forward(const GaussianView& gaussians, const Camera& camera) {
  last_ = rasterize(gaussians, camera, settings_, device_);
  return rendered_from_raster(last_);
}

void RasterRenderer::backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) {
  GBufferGrad go;
  go.color = d.color;
  go.alpha = d.alpha;
  go.depth = d.depth;
  go.median_depth = d.median_depth;
  go.normal = d.normal;
  go.extras = d.extras;
  rasterize_backward(gaussians, last_.state, go, grads);
  backward_detached_extras(gaussians, last_.state, d.extras_detached, grads);
}

double RasterRenderer::depth_distortion(const GaussianView& gaussians, const Camera& camera,
                                        const DistortionDepthRange& range, float weight, const float* pixel_weight,
                                        const GaussianGradView& grads) {
  return depth_distortion_pass(gaussians, camera, settings_, range, weight, pixel_weight, grads, device_);
}

void backward_detached_extras(const GaussianView& gaussians, const RasterState& state, const float* d_extras,
                              const GaussianGradView& grads) {
  if (!d_extras || !grads.extras) return;
  GBufferGrad go;
  go.extras = d_extras;
  GaussianGradView only_extras;
  only_extras.extras = grads.extras;
  rasterize_backward(gaussians, state, go, only_extras);
}

}  // namespace goris
