#include "render/removal/selection_view_masks.h"

#include <string>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/removal/select_view.h"

namespace goris {

RasterOutput render_selection_channel(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                                      const RasterSettings& raster) {
  const std::size_t n = model.count();
  if (mask.size() != n)
    throw Error("selection", "mask has " + std::to_string(mask.size()) + " entries for " + std::to_string(n) +
                                 " Gaussians");
  std::vector<float> sel(n);
  for (std::size_t i = 0; i < n; ++i) sel[i] = mask[i] ? 1.0f : 0.0f;
  const Buffer<float> sel_buf(sel, model.device());
  GaussianView view = plain_gaussian_view(model);
  view.extras = sel_buf.data();
  view.n_extras = 1;
  return rasterize(view, camera, raster, model.device());
}

Mask selection_view_mask(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                         const RasterSettings& raster, const ViewMaskSettings& s) {
  if (!(s.threshold > 0.0f && s.threshold < 1.0f)) throw Error("masks", "the coverage threshold must lie in (0, 1)");
  const std::vector<float> cov = render_selection_channel(model, mask, camera, raster).gbuffer.extras.to_host();
  Mask m(camera.width, camera.height);
  for (std::size_t p = 0; p < m.data.size(); ++p) m.data[p] = cov[p] > s.threshold ? 255 : 0;
  return open_mask(close_mask(m, s.close_radius), s.open_radius);
}

std::string object_mask_file_name(const std::string& name) {
  return name.rfind("r_", 0) == 0 ? "mask_" + name.substr(2) + ".png" : name + ".png";
}

double mask_iou(const Mask& a, const Mask& b) {
  if (a.width != b.width || a.height != b.height)
    throw Error("masks", "IoU of masks of different sizes (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                             " and " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  std::size_t inter = 0, uni = 0;
  for (std::size_t p = 0; p < a.data.size(); ++p) {
    const bool x = a.data[p] != 0, y = b.data[p] != 0;
    inter += x && y;
    uni += x || y;
  }
  return uni ? double(inter) / double(uni) : 1.0;
}

}  // namespace goris
