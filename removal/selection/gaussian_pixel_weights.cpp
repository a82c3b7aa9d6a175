#include "removal/selection/gaussian_pixel_weights.h"

#include <string>

#include "core/util/error.h"
#include "removal/selection/select_view.h"
#include "render/raster/rasterizer.h"

namespace goris {

PixelWeights gaussian_pixel_weights(const GaussianModel& model, const std::vector<Camera>& cameras,
                                    const std::vector<Mask>& masks, const RasterSettings& raster) {
  if (masks.size() != cameras.size())
    throw Error("pixel weights", std::to_string(masks.size()) + " masks for " + std::to_string(cameras.size()) +
                                     " cameras");
  const std::size_t n = model.count();
  PixelWeights w;
  w.inside.assign(n, 0.0f);
  w.outside.assign(n, 0.0f);
  if (n == 0) return w;
  const Device dev = model.device();
  const Buffer<float> ones(std::vector<float>(n, 1.0f), dev);
  GaussianView view = plain_gaussian_view(model);
  view.extras = ones.data();
  view.n_extras = 1;
  for (std::size_t v = 0; v < cameras.size(); ++v) {
    const Camera& cam = cameras[v];
    const Mask& mask = masks[v];
    if (mask.width != cam.width || mask.height != cam.height)
      throw Error("pixel weights", "mask " + std::to_string(v) + " is " + std::to_string(mask.width) + "x" +
                                       std::to_string(mask.height) + ", its camera " + std::to_string(cam.width) +
                                       "x" + std::to_string(cam.height));
    const RasterOutput fwd = rasterize(view, cam, raster, dev);
    for (const bool in : {true, false}) {
      std::vector<float> g(mask.data.size());
      for (std::size_t p = 0; p < g.size(); ++p) g[p] = (mask.data[p] != 0) == in ? 1.0f : 0.0f;
      const Buffer<float> grad_img(g, dev);
      Buffer<float> grad(std::vector<float>(n, 0.0f), dev);
      GBufferGrad go;
      go.extras = grad_img.data();
      GaussianGradView gv;
      gv.extras = grad.data();
      rasterize_backward(view, fwd.state, go, gv);
      const std::vector<float> h = grad.to_host();
      std::vector<float>& dst = in ? w.inside : w.outside;
      for (std::size_t k = 0; k < n; ++k) dst[k] += h[k];
    }
  }
  return w;
}

}  // namespace goris
