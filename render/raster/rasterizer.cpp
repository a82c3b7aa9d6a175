// Public entry points: validate, convert the scene model's views, dispatch to the CPU or CUDA driver.
#include "render/raster/rasterizer.h"

#include "core/compute/cuda_dispatch.h"
#include "core/util/error.h"
#include "render/raster/raster_cpu.h"
#include "render/raster/rasterizer_cuda.h"

namespace goris {

GaussiansT<float> to_raster_view(const GaussianView& v) {
  GaussiansT<float> g;
  g.count = v.count;
  g.positions = v.positions;
  g.log_scales = v.log_scales;
  g.rotations = v.rotations;
  g.opacity_logits = v.opacity_logits;
  g.sh = v.sh;
  g.sh_degree = v.sh_degree;
  g.extras = v.extras;
  g.n_extras = v.n_extras;
  g.filter3d_var = v.filter3d_var;
  return g;
}

GaussianGradsT<float> to_raster_grads(const GaussianGradView& v) {
  GaussianGradsT<float> g;
  g.positions = v.positions;
  g.log_scales = v.log_scales;
  g.rotations = v.rotations;
  g.opacity_logits = v.opacity_logits;
  g.sh = v.sh;
  g.extras = v.extras;
  g.mean2d_grad_norm = v.mean2d_grad_norm;
  return g;
}

RasterOutput rasterize(const GaussianView& gaussians, const Camera& camera, const RasterSettings& settings,
                       Device device) {
  RasterOutput out;
  const GaussiansT<float> g = to_raster_view(gaussians);
  if (device == Device::CUDA) {
    raster::validate_inputs(g, camera);
    GORIS_CUDA_CALL("rasterizer", raster::forward_cuda(g, camera, settings, out.gbuffer, out.state));
  } else {
    raster::forward_cpu(g, camera, settings, out.gbuffer, out.state);
  }
  return out;
}

void rasterize_backward(const GaussianView& gaussians, const RasterState& state, const GBufferGrad& grad_out,
                        const GaussianGradView& grads) {
  const GaussiansT<float> g = to_raster_view(gaussians);
  if (state.device == Device::CUDA)
    GORIS_CUDA_CALL("rasterizer", raster::backward_cuda(g, state, grad_out, to_raster_grads(grads)));
  else
    raster::backward_cpu(g, state, grad_out, to_raster_grads(grads));
}

}  // namespace goris
