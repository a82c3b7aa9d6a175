#pragma once
// Differentiable tile-based Gaussian rasterizer (3DGS tiles, RaDe-GS depth planes and normals) that renders
// a G-buffer and back-propagates gradients on every channel to every Gaussian parameter.
//
//   auto fwd = rasterize(view, camera, settings, Device::CPU);       // fwd.gbuffer: colour, alpha, depth, ...
//   ... loss writes dL/d(channel) images ...
//   rasterize_backward(view, fwd.state, dl_dgbuffer, grads);         // grads.* += dL/dparameter
//
// Conventions: camera per core/io/camera.h (world-to-camera, OpenCV axes, pixel centres at +0.5, no
// distortion); Gaussians per core/scene/gaussian_view.h. Front-to-back blending with alpha = min(0.99, o G),
// Gaussians with alpha < 1/255 or power > 0 skipped, a pixel stops before the Gaussian that would bring
// T (1 - alpha) below 1e-4. Types and per-channel layouts: render/raster/raster_types.h.
#include "core/compute/device.h"
#include "core/io/camera.h"
#include "core/scene/gaussian_view.h"
#include "render/raster/raster_types.h"

namespace goris {

using GBuffer = GBufferT<float>;
using GBufferGrad = GBufferGradT<float>;
using RasterState = RasterStateT<float>;

struct RasterOutput {
  GBuffer gbuffer;
  RasterState state;  // what rasterize_backward needs; keep it alive until then
};

// Renders `gaussians` (pointers on `device`) seen by `camera` into a G-buffer on `device`.
// Throws goris::Error for an invalid camera (size, focal length, distortion) or view (null pointers,
// sh_degree outside 0..3, extras missing), or a CUDA device in a build without CUDA.
RasterOutput rasterize(const GaussianView& gaussians, const Camera& camera, const RasterSettings& settings,
                       Device device);

// Adds dL/dparameters to `grads` (+=, pointers on the forward pass's device; null ones skipped) given
// dL/d(G-buffer) `grad_out`. `gaussians` must hold the same values as in the forward pass.
// grads.mean2d_grad_norm accumulates |dL/dmean2d| in pixels (3DGS's NDC statistic is the pixel gradient
// scaled by (W/2, H/2) component-wise) for every Gaussian with state.radii > 0.
void rasterize_backward(const GaussianView& gaussians, const RasterState& state, const GBufferGrad& grad_out,
                        const GaussianGradView& grads);

// Float views of the scene model's types as the templated internals read them.
GaussiansT<float> to_raster_view(const GaussianView& v);
GaussianGradsT<float> to_raster_grads(const GaussianGradView& g);

}  // namespace goris
