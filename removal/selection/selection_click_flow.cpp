#include "removal/selection/selection_click_flow.h"

#include <algorithm>
#include <cstdio>

#include "core/util/error.h"
#include "core/scene/plane_from_masks.h"
#include "removal/selection/selection_view_masks.h"

namespace goris {

ClickOutcome click_in_view(const GaussianModel& model, const View& view, const Image& photo, int x, int y,
                           const RasterSettings& raster, bool region, const std::vector<float>* glossy) {
  const std::string at = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
  if (x < 0 || y < 0 || x >= view.camera.width || y >= view.camera.height)
    throw Error("--click", at + " is outside view " + view.name + " (" + std::to_string(view.camera.width) + "x" +
                               std::to_string(view.camera.height) + " at the run's training resolution)");
  ClickOutcome o;
  o.pick = pick_gaussian(model, view.camera, x, y);
  if (!o.pick.hit) {
    char alpha[32];
    std::snprintf(alpha, sizeof alpha, "%g", double(o.pick.ray_alpha));
    throw Error("--click", at + " of view " + view.name + " shows background (the ray's opacity is " + alpha +
                               "): click on the object");
  }
  if (region)
    o.region = grow_click_region(photo, render_median_depth(model, view.camera, raster), x, y, {}, glossy);
  return o;
}

std::vector<const std::vector<float>*> glossy_mask_pointers(const std::vector<std::vector<float>>& masks) {
  std::vector<const std::vector<float>*> out;
  for (const std::vector<float>& m : masks) out.push_back(m.empty() ? nullptr : &m);
  return out;
}

MirrorPlane support_plane_of_click_selection(const SelectionPoints& pts, const SelectionMask& seeds,
                                             const std::vector<View>& views,
                                             const std::vector<const std::vector<float>*>& glossy_masks) {
  if (std::none_of(glossy_masks.begin(), glossy_masks.end(), [](const auto* m) { return m != nullptr; })) return {};
  const std::vector<Camera> cameras = cameras_of(views);
  return plane_from_glossy_masks(cameras, glossy_masks, {},
                                 target_rest_heights(cameras, glossy_masks, pts.position, seeds))
      .plane;
}

std::size_t drop_beyond_plane(const SelectionPoints& pts, const MirrorPlane& plane, SelectionMask& selection) {
  if (!plane.found) return 0;
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < selection.size(); ++i)
    if (selection[i] && plane.signed_distance(glm::dvec3(pts.position[i])) < -plane.tolerance) {
      selection[i] = 0;
      ++dropped;
    }
  return dropped;
}

ClickSelection select_by_click_regions(const GaussianModel& model, const SelectionPoints& pts,
                                       const std::vector<ClickView>& regions, const std::vector<View>& views,
                                       const RasterSettings& raster, const CloseSettings& close,
                                       const std::vector<const std::vector<float>*>& glossy_masks) {
  ClickSelection s;
  SelectionMask voted = select_from_click_regions(model, regions, raster);
  s.support = support_plane_of_click_selection(pts, voted, views, glossy_masks);
  // Each step can bring the reflection back (the hull of a selection that reaches below the surface, a
  // silhouette that covers the mirror world), so it is dropped after each.
  auto close_above = [&](SelectionMask m) {
    s.beyond_support += drop_beyond_plane(pts, s.support, m);
    SelectionResult r = close_selection(pts, m, close);
    s.beyond_support += drop_beyond_plane(pts, s.support, r.mask);
    r.summary.selected = count_selected(r.mask);
    return r;
  };
  s.result = close_above(std::move(voted));
  s.from_clicked_views = s.result.summary.selected;
  if (s.result.summary.seeds > 0 && regions.size() > 1) {
    const SelectionMask revoted = revote_with_view_masks(model, s.result.mask, views, raster, glossy_masks);
    if (count_selected(revoted) > 0) {
      s.result = close_above(revoted);
      s.revoted = true;
    }
  }
  return s;
}

}  // namespace goris
