#pragma once
// A click's object as a 2D region of the clicked view, lifted to the Gaussians (`goris select --click`
// without --grow; the two-click workflow on a capture without object masks).
//
// Per click (view V, pixel p): the region is flood-filled from p over 4-neighbours that continue the
// surface in the run's median depth (a step of at most depth_step of the depth: occluding contours stop
// it) and whose photo colour lies within a tolerance of the click's colour (the 5x5 median around p in the
// training photo: contact lines between touching surfaces of different colour stop it); it never enters the
// view's glossy pixels where the run has glossy masks (the surface the target stands on). The tolerance is
// not a user setting: it climbs a ladder, and the region is the last one before the area jumps by more
// than leak_ratio from one rung to the next (the fill has crossed a weak edge into the surroundings) or
// exceeds max_area_fraction of the view (the ladder reaches 0.80: a metal object's reflections span a wide
// range of colours, and the depth steps at its silhouette still bound the fill).
//
// The clicked views' regions then act as object masks, read by rendered weight rather than by centres: a
// Gaussian's weight in a pixel is its alpha * T there (gaussian_pixel_weights). In each clicked view where
// its weight reaches min_weight pixels, at least min_inside_share of that weight must fall inside the view's
// region; it is selected when that holds in every such view and there is at least one. The second click's
// view prunes what the first view's region let through and vice versa (a floor Gaussian under the object
// shows mostly floor in one of the views), while a large or elongated Gaussian of the object whose centre
// projects just outside a region, or hides behind its own neighbours, still counts; one hidden in both
// clicked views is left to the closing and to the other views' vote. The share is low (0.1) because that
// vote (revote_with_view_masks) removes what the clicked views let through better than a strict share does.
// The caller closes the result (close_selection) for the object's interior and far side, and lets every
// training view vote once more (revote_with_view_masks).
#include <cstdint>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/scene/selection_points.h"
#include "render/raster/raster_types.h"

namespace goris {

class GaussianModel;

struct ClickRegionSettings {
  float depth_step = 0.02f;                 // relative depth change allowed between neighbouring pixels
  std::vector<float> colour_ladder = {0.04f, 0.06f, 0.08f, 0.10f, 0.13f, 0.16f, 0.20f,
                                      0.25f, 0.30f, 0.35f, 0.40f, 0.50f, 0.60f, 0.80f};  // RGB distance
  float leak_ratio = 1.6f;                  // area growth between rungs that counts as a leak ...
  float leak_area_fraction = 0.02f;         // ... when it also adds this fraction of the view's pixels
  float max_area_fraction = 0.4f;           // of the view's pixels
};

struct ClickRegion {
  Mask mask;              // the region (empty when the click pixel has no depth)
  float tolerance = 0.0f; // the ladder rung it was taken at
  std::size_t area = 0;
  bool leaked_at_first = false;  // even the first rung leaked: the region is the first rung's
  std::vector<std::size_t> rung_areas;  // the fill's area at every rung of the ladder
};

// The region grown from pixel (x, y) of an RGB photo (values in [0, 1]) and the render's median depth of
// the same view (0 = nothing rendered there: never part of the region). `barrier` (optional, [H][W] in
// [0, 1]): pixels above one half are never part of it; the view's glossy mask, which marks the surface the
// target stands on and never the target: the fill cannot leave the target across its foot, where the depth
// runs on into the surface, so the ladder climbs to the tolerance a textured target needs. Throws
// goris::Error on mismatched sizes or a pixel outside the image.
ClickRegion grow_click_region(const Image& photo, const std::vector<float>& median_depth, int x, int y,
                              const ClickRegionSettings& settings = {}, const std::vector<float>* barrier = nullptr);

// The median depth of the model's render of `camera` (CPU vector, [H][W]).
std::vector<float> render_median_depth(const GaussianModel& model, const Camera& camera, const RasterSettings& raster);

struct ClickView {
  std::string name;
  Camera camera;
  Mask region;
};
// The clicked views' regions lifted to the Gaussians as described above.
struct WeightVoteSettings {
  float min_inside_share = 0.1f;  // of the Gaussian's weight in a clicked view
  float min_weight = 0.05f;       // pixels: less weight in a view = hidden there, no say
};
SelectionMask select_from_click_regions(const GaussianModel& model, const std::vector<ClickView>& views,
                                        const RasterSettings& raster = {}, const WeightVoteSettings& settings = {});

// One pass of "masks from the selection, selection from the masks": every view's object mask is the
// selection's silhouette (selection_silhouette_mask, selection_view_masks.h) less the view's glossy pixels,
// and the masks vote as the data set's would (labels_from_masks, default settings). Two clicked views see the
// object from two sides only; the vote of every view drops what the other views see outside the object and
// adds what they see inside it. A glossy mask marks the visible surface and never what stands in front of it, so its pixels are
// no object (the table seen through a holed target's hole, the target's reflection in it). The caller
// closes the result. glossy[k] is views[k]'s glossy mask at the camera's size in [0, 1] (null or absent:
// none).
SelectionMask revote_with_view_masks(const GaussianModel& model, const SelectionMask& selection,
                                     const std::vector<View>& views, const RasterSettings& raster = {},
                                     const std::vector<const std::vector<float>*>& glossy = {});

}  // namespace goris
