#include "render/removal/unsupported_gaussians.h"

#include <string>

#include "core/inpaint/mask.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/removal/inpaint_mask_scene.h"
#include "render/removal/select_view.h"
#include "render/removal/selection_view_masks.h"

namespace goris {

UnsupportedWeights unsupported_weights(const GaussianModel& model, const std::vector<std::uint8_t>& selected,
                                       const std::vector<Camera>& cameras, const RasterSettings& raster,
                                       const UnsupportedSettings& s) {
  const std::size_t n = model.count();
  if (selected.size() != n)
    throw Error("unsupported Gaussians", "selection has " + std::to_string(selected.size()) + " entries for " +
                                             std::to_string(n) + " Gaussians");
  UnsupportedWeights w;
  w.inside.assign(n, 0.0f);
  w.outside.assign(n, 0.0f);
  std::vector<std::size_t> kept_index;  // kept Gaussian k -> index in the full model
  for (std::size_t i = 0; i < n; ++i)
    if (!selected[i]) kept_index.push_back(i);
  if (kept_index.empty()) return w;
  const SplitScene split = split_removed(model, selected);
  const std::size_t m = split.kept.count();
  const Device dev = model.device();
  const Buffer<float> ones(std::vector<float>(m, 1.0f), dev);
  GaussianView view = plain_gaussian_view(split.kept);
  view.extras = ones.data();
  view.n_extras = 1;
  for (const Camera& cam : cameras) {
    const std::vector<float> cov = render_selection_channel(model, selected, cam, raster).gbuffer.extras.to_host();
    Mask inside(cam.width, cam.height);
    for (std::size_t p = 0; p < inside.data.size(); ++p) inside.data[p] = cov[p] > s.coverage_threshold ? 255 : 0;
    const RasterOutput fwd = rasterize(view, cam, raster, dev);
    for (const bool in : {true, false}) {
      std::vector<float> g(inside.data.size());
      for (std::size_t p = 0; p < g.size(); ++p) g[p] = (inside.data[p] != 0) == in ? 1.0f : 0.0f;
      const Buffer<float> grad_img(g, dev);
      Buffer<float> grad(std::vector<float>(m, 0.0f), dev);
      GBufferGrad go;
      go.extras = grad_img.data();
      GaussianGradView gv;
      gv.extras = grad.data();
      rasterize_backward(view, fwd.state, go, gv);
      const std::vector<float> h = grad.to_host();
      std::vector<float>& dst = in ? w.inside : w.outside;
      for (std::size_t k = 0; k < m; ++k) dst[kept_index[k]] += h[k];
    }
  }
  return w;
}

std::vector<std::uint8_t> unsupported_gaussians(const UnsupportedWeights& w, const std::vector<std::uint8_t>& selected,
                                                const UnsupportedSettings& s) {
  std::vector<std::uint8_t> out(selected.size(), 0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (selected[i]) continue;
    const float in = w.inside[i], total = in + w.outside[i];
    out[i] = in >= s.min_inside_px && w.outside[i] < s.max_outside_share * total && w.outside[i] < s.max_outside_px;
  }
  return out;
}

}  // namespace goris
