#pragma once
// `goris select --click` by region (its default) as steps, so the CLI and the editor's two-click flow run
// the same code: each click's picked Gaussian and region of its training view (selection_click_region.h),
// then the regions lifted to the Gaussians by rendered weight, closed, and with two clicks or more voted
// once more by every training view's silhouette of the selection and closed again.
#include <cstddef>
#include <string>
#include <vector>

#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"
#include "removal/selection/selection_click_region.h"
#include "removal/selection/selection_labels.h"
#include "removal/selection/selection_pick.h"
#include "render/raster/raster_types.h"

namespace goris {

class GaussianModel;

struct ClickOutcome {
  PickResult pick;     // the Gaussian the pixel shows
  ClickRegion region;  // the click's region of its view
};

// The click at pixel (x, y) of `view` (at the model's training resolution; `photo` is the view's photo at
// the camera's size, unused without `region`: the pick alone). `glossy`: the view's glossy mask at the
// camera's size (null: none), whose pixels the region never enters (grow_click_region's barrier). Throws
// goris::Error for a pixel outside the view or one that shows background.
ClickOutcome click_in_view(const GaussianModel& model, const View& view, const Image& photo, int x, int y,
                           const RasterSettings& raster, bool region = true,
                           const std::vector<float>* glossy = nullptr);

struct ClickSelection {
  SelectionResult result;              // the selection (result.summary.seeds == 0: nothing found)
  std::size_t from_clicked_views = 0;  // selected from the clicked views alone, before every view's vote
  bool revoted = false;                // every view's vote was taken (two regions or more, and it kept some)
  MirrorPlane support;                 // the glossy surface the target stands on (found = false: none)
  std::size_t beyond_support = 0;      // Gaussians dropped beyond it (over all steps, with repeats)
};

// The clicked views' regions lifted (select_from_click_regions) and closed; with two regions or more,
// voted by every view in `views` (revote_with_view_masks) and closed again, unless that vote keeps nothing.
// glossy_masks[k] is views[k]'s glossy mask ([0, 1] at the camera's size; null: none). With any, the glossy
// surface the target stands on is found from them (support_plane_of_click_selection), and what lies beyond
// it is left out at every step: over a mirror-like surface a model shows the target's reflection as a copy
// of it behind the surface (a mirror world), inside the clicked regions and the silhouettes of many views,
// and it is not the target (the removal deals with reflections).
ClickSelection select_by_click_regions(const GaussianModel& model, const SelectionPoints& pts,
                                       const std::vector<ClickView>& regions, const std::vector<View>& views,
                                       const RasterSettings& raster, const CloseSettings& close = {},
                                       const std::vector<const std::vector<float>*>& glossy_masks = {});

// The views' glossy masks as select_by_click_regions reads them: a pointer to each, null where a view has none.
std::vector<const std::vector<float>*> glossy_mask_pointers(const std::vector<std::vector<float>>& masks);

// The plane of the views' glossy masks (plane_from_glossy_masks) searched where the selected Gaussians rest
// (target_rest_heights). found = false without glossy masks or without a plane through them.
MirrorPlane support_plane_of_click_selection(const SelectionPoints& pts, const SelectionMask& seeds,
                                             const std::vector<View>& views,
                                             const std::vector<const std::vector<float>*>& glossy_masks);

// Clears the selected Gaussians whose centre lies beyond `plane` (on the side away from its normal) by more
// than its tolerance; returns how many. Nothing without a plane (found = false).
std::size_t drop_beyond_plane(const SelectionPoints& pts, const MirrorPlane& plane, SelectionMask& selection);

}  // namespace goris
