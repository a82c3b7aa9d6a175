#pragma once
// The CPU rasterizer, templated on the scalar type (float in production through rasterizer.h, double in
// the gradient tests). Same contract as rasterize / rasterize_backward.
#include <string>

#include "core/util/error.h"
#include "render/raster/blend.h"
#include "render/raster/raster_types.h"

namespace goris::raster {

template <class T>
void forward_cpu(const GaussiansT<T>& g, const Camera& cam, const RasterSettings& settings, GBufferT<T>& out,
                 RasterStateT<T>& st);

template <class T>
void backward_cpu(const GaussiansT<T>& g, const RasterStateT<T>& st, const GBufferGradT<T>& grad_out,
                  const GaussianGradsT<T>& out);

// Throws goris::Error naming the problem for cameras and views the rasterizer cannot render.
template <class T>
void validate_inputs(const GaussiansT<T>& g, const Camera& cam) {
  const std::string who = "rasterizer";
  if (cam.width <= 0 || cam.height <= 0)
    throw Error(who, "camera image size " + std::to_string(cam.width) + "x" + std::to_string(cam.height) + " is empty");
  if (cam.width > 65536 || cam.height > 65536) throw Error(who, "camera image size exceeds 65536 pixels per side");
  if (!(cam.fx > 0) || !(cam.fy > 0)) throw Error(who, "camera focal lengths must be positive");
  if (cam.has_distortion()) throw Error(who, "camera has lens distortion; the rasterizer needs undistorted images");
  if (g.count < 0) throw Error(who, "negative Gaussian count");
  if (g.sh_degree < 0 || g.sh_degree > 3)
    throw Error(who, "SH degree " + std::to_string(g.sh_degree) + " is outside 0..3");
  if (g.n_extras < 0 || g.n_extras > kMaxExtras)
    throw Error(who, std::to_string(g.n_extras) + " extra channels (at most " + std::to_string(kMaxExtras) + ")");
  if (g.count > 0 && (!g.positions || !g.log_scales || !g.rotations || !g.opacity_logits || !g.sh))
    throw Error(who, "Gaussian view has null parameter arrays");
  if (g.count > 0 && g.n_extras > 0 && !g.extras) throw Error(who, "Gaussian view declares extras but has none");
}

}  // namespace goris::raster
