#include "render/removal/unsupported_gaussians.h"

#include <string>

#include "core/inpaint/mask.h"
#include "core/util/error.h"
#include "render/removal/gaussian_pixel_weights.h"
#include "render/removal/inpaint_mask_scene.h"
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
  std::vector<Mask> target_pixels;
  for (const Camera& cam : cameras) {
    const std::vector<float> cov = render_selection_channel(model, selected, cam, raster).gbuffer.extras.to_host();
    Mask m(cam.width, cam.height);
    for (std::size_t p = 0; p < m.data.size(); ++p) m.data[p] = cov[p] > s.coverage_threshold ? 255 : 0;
    target_pixels.push_back(std::move(m));
  }
  const PixelWeights kw = gaussian_pixel_weights(split_removed(model, selected).kept, cameras, target_pixels, raster);
  for (std::size_t k = 0; k < kept_index.size(); ++k) {
    w.inside[kept_index[k]] = kw.inside[k];
    w.outside[kept_index[k]] = kw.outside[k];
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
