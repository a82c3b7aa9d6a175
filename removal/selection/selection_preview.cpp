#include "removal/selection/selection_preview.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/selection/select_view.h"
#include "removal/selection/selection_view_masks.h"
#include "render/raster/rasterizer.h"

namespace goris {

Image render_selection_preview(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                               const RasterSettings& raster, const PreviewSettings& ps) {
  const std::size_t n = model.count();
  if (mask.size() != n)
    throw Error("preview", "mask has " + std::to_string(mask.size()) + " entries for " + std::to_string(n) +
                               " Gaussians");
  const Device dev = model.device();
  // Removed: opacity ~1e-13, below the 1/255 cut, so the selected Gaussians are skipped.
  std::vector<float> opacity = model.tensor(Param::OpacityLogit).value.to_host();
  for (std::size_t i = 0; i < n; ++i)
    if (mask[i]) opacity[i] = -30.0f;
  const Buffer<float> removed_opacity(opacity, dev);
  GaussianView removed_view = plain_gaussian_view(model);
  removed_view.opacity_logits = removed_opacity.data();

  const RasterOutput a = render_selection_channel(model, mask, camera, raster);
  const RasterOutput b = rasterize(removed_view, camera, raster, dev);
  const std::vector<float> ca = a.gbuffer.color.to_host(), cov = a.gbuffer.extras.to_host(),
                           cb = b.gbuffer.color.to_host();
  const int w = camera.width, h = camera.height;
  const std::size_t hw = std::size_t(w) * std::size_t(h);
  Image out(2 * w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * w + x;
      const float s = std::min(1.0f, std::max(0.0f, cov[p])) * ps.strength;
      float* left = &out.pixels[(std::size_t(y) * 2 * w + x) * 3];
      float* right = &out.pixels[(std::size_t(y) * 2 * w + w + x) * 3];
      for (int c = 0; c < 3; ++c) {
        left[c] = ca[c * hw + p] * (1.0f - s) + ps.tint[c] * s;
        right[c] = cb[c * hw + p];
      }
    }
  return out;
}

}  // namespace goris
