#include "render/train/raster_renderer.h"

namespace goris {

RasterSettings RasterRenderer::settings_for(const TrainConfig& config) {
  RasterSettings s = config.filter_2d ? RasterSettings::mip_splatting() : RasterSettings::classic_3dgs();
  s.background = config.background;
  return s;
}

RenderedImages RasterRenderer::forward(const GaussianView& gaussians, const Camera& camera) {
  last_ = rasterize(gaussians, camera, settings_, device_);
  const GBuffer& g = last_.gbuffer;
  RenderedImages r;
  r.width = g.width;
  r.height = g.height;
  r.color = g.color.data();
  r.alpha = g.alpha.data();
  r.depth = g.depth.data();
  r.median_depth = g.median_depth.data();
  r.normal = g.normal.data();
  r.radii = last_.state.radii.data();
  return r;
}

void RasterRenderer::backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) {
  GBufferGrad go;
  go.color = d.color;
  go.alpha = d.alpha;
  go.depth = d.depth;
  go.median_depth = d.median_depth;
  go.normal = d.normal;
  rasterize_backward(gaussians, last_.state, go, grads);
}

}  // namespace goris
