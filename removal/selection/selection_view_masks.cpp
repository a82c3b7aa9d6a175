#include "removal/selection/selection_view_masks.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/selection/select_view.h"
#include "render/raster/rasterizer.h"

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

namespace {

// A coverage image thresholded and cleaned as ViewMaskSettings says.
Mask coverage_mask(const std::vector<float>& coverage, const Camera& camera, const ViewMaskSettings& s) {
  if (!(s.threshold > 0.0f && s.threshold < 1.0f)) throw Error("masks", "the coverage threshold must lie in (0, 1)");
  Mask m(camera.width, camera.height);
  for (std::size_t p = 0; p < m.data.size(); ++p) m.data[p] = coverage[p] > s.threshold ? 255 : 0;
  return open_mask(close_mask(m, s.close_radius), s.open_radius);
}

}  // namespace

Mask selection_view_mask(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                         const RasterSettings& raster, const ViewMaskSettings& s) {
  return coverage_mask(render_selection_channel(model, mask, camera, raster).gbuffer.extras.to_host(), camera, s);
}

SelectionViewMasks selection_view_masks(const GaussianModel& model, const SelectionMask& mask,
                                        const std::vector<Camera>& cameras, const RasterSettings& raster,
                                        const ViewMaskSettings& s, const std::function<void(std::size_t)>& on_view) {
  SelectionViewMasks out;
  out.threshold = s.threshold;
  bool any = false;
  for (std::size_t v = 0; v < cameras.size(); ++v) {
    if (on_view) on_view(v);
    const std::vector<float> c = render_selection_channel(model, mask, cameras[v], raster).gbuffer.extras.to_host();
    for (float x : c) out.peak = std::max(out.peak, x);
    out.masks.push_back(coverage_mask(c, cameras[v], s));
    any = any || count_set(out.masks.back()) > 0;
  }
  if (any || !(out.peak > 0.0f) || 0.5f * out.peak >= s.threshold) return out;
  ViewMaskSettings lower = s;
  lower.threshold = 0.5f * out.peak;
  out.threshold = lower.threshold;
  out.lowered = true;
  for (std::size_t v = 0; v < cameras.size(); ++v)  // rendered again: keeping every view's coverage costs memory
    out.masks[v] = coverage_mask(render_selection_channel(model, mask, cameras[v], raster).gbuffer.extras.to_host(),
                                 cameras[v], lower);
  return out;
}

Mask selection_silhouette_mask(const GaussianModel& model, const SelectionMask& selection, const Camera& camera,
                               const RasterSettings& raster, const ViewMaskSettings& s) {
  if (selection.size() != model.count())
    throw Error("selection", "mask has " + std::to_string(selection.size()) + " entries for " +
                                 std::to_string(model.count()) + " Gaussians");
  std::vector<float> opacity = model.tensor(Param::OpacityLogit).value.to_host();
  for (std::size_t i = 0; i < opacity.size(); ++i)
    if (!selection[i]) opacity[i] = -40.0f;  // sigmoid(-40) ~ 4e-18: transparent
  const Buffer<float> opacity_buf(opacity, model.device());
  GaussianView gv = plain_gaussian_view(model);
  gv.opacity_logits = opacity_buf.data();
  return coverage_mask(rasterize(gv, camera, raster, model.device()).gbuffer.alpha.to_host(), camera, s);
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
