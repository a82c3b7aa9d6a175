#pragma once
// Object masks from a 3D selection: per view, the rendered coverage of the selected Gaussians (the
// selection rasterized as an extra channel of the full model, so their alpha * T already accounts for
// everything in front of them: a depth test against the full render), thresholded and cleaned by a small
// morphological close then open. Written as the data sets' object masks are named (mask_XXX.png for
// view r_XXX, else <view name>.png), so `goris select --masks DIR`, the label loss and stage 2 read them.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/io/dataset.h"
#include "core/scene/selection_points.h"
#include "render/raster/rasterizer.h"

namespace goris {

class GaussianModel;

// The full render with the selection as its one extra channel: gbuffer.color is the view,
// gbuffer.extras the selected Gaussians' coverage sum(alpha_i T_i) per pixel. Throws goris::Error when the
// mask size differs from the model's.
RasterOutput render_selection_channel(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                                      const RasterSettings& raster = {});

struct ViewMaskSettings {
  float threshold = 0.5f;  // coverage above which a pixel is the object
  int close_radius = 1;    // pixels: fills pinholes between splats
  int open_radius = 1;     // pixels: drops specks from stray selected Gaussians
};

Mask selection_view_mask(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                         const RasterSettings& raster = {}, const ViewMaskSettings& settings = {});

// Every camera's selection_view_mask, for writing a selection's object masks. A selection whose coverage stays
// at or under the threshold in every view - a fog of faint Gaussians, as a short radiance run makes of an
// object over a rough floor - would give an empty mask in every view and a removal with nothing to inpaint: then
// every view is cut at half the selection's peak coverage over all views instead (`lowered`), so that the
// masks hold where the selection dominates. A selection no view sees (peak 0) keeps its empty masks.
struct SelectionViewMasks {
  std::vector<Mask> masks;  // one per camera
  float peak = 0.0f;        // the selection's largest coverage of any pixel of any view
  float threshold = 0.0f;   // the threshold the masks were cut at
  bool lowered = false;     // threshold = peak / 2 < settings.threshold (every view was empty at the setting's)
};
SelectionViewMasks selection_view_masks(const GaussianModel& model, const SelectionMask& mask,
                                        const std::vector<Camera>& cameras, const RasterSettings& raster = {},
                                        const ViewMaskSettings& settings = {},
                                        const std::function<void(std::size_t view)>& on_view = {});

// The selected Gaussians rendered alone (every other one transparent), their coverage thresholded and
// cleaned as selection_view_mask's is. Unlike the coverage in the full render it also covers the selection's
// parts hidden behind unselected Gaussians: a selection that holds one side of an object (the side two
// clicked views saw) covers the object's whole outline from the far side (the two clicks' every-view vote,
// revote_with_view_masks). Throws goris::Error when the mask size differs from the model's.
Mask selection_silhouette_mask(const GaussianModel& model, const SelectionMask& selection, const Camera& camera,
                               const RasterSettings& raster = {}, const ViewMaskSettings& settings = {});

// The file name a view's object mask has: mask_XXX.png for r_XXX, else <name>.png.
std::string object_mask_file_name(const std::string& view_name);

// Intersection over union of the set pixels (1 when both are empty). Different sizes: goris::Error.
double mask_iou(const Mask& a, const Mask& b);

}  // namespace goris
