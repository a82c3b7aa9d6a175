#include "render/removal/selection_click_flow.h"

#include <cstdio>

#include "core/util/error.h"
#include "render/removal/selection_view_masks.h"

namespace goris {

ClickOutcome click_in_view(const GaussianModel& model, const View& view, const Image& photo, int x, int y,
                           const RasterSettings& raster, bool region) {
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
  if (region) o.region = grow_click_region(photo, render_median_depth(model, view.camera, raster), x, y);
  return o;
}

ClickSelection select_by_click_regions(const GaussianModel& model, const SelectionPoints& pts,
                                       const std::vector<ClickView>& regions, const std::vector<View>& views,
                                       const RasterSettings& raster, const CloseSettings& close) {
  ClickSelection s;
  const SelectionMask voted = select_from_click_regions(model, regions, raster);
  s.result = close_selection(pts, voted, close);
  s.from_clicked_views = s.result.summary.selected;
  if (s.result.summary.seeds > 0 && regions.size() > 1) {
    const SelectionMask revoted = revote_with_view_masks(model, s.result.mask, views, raster);
    if (count_selected(revoted) > 0) {
      s.result = close_selection(pts, revoted, close);
      s.revoted = true;
    }
  }
  return s;
}

}  // namespace goris
