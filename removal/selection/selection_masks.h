#pragma once
// Selecting the target from 2D object masks (mask_XXX.png, or masks painted in the editor): every Gaussian
// centre votes in each masked view where it is visible, and a Gaussian is selected when it falls inside the
// mask in at least min_fraction of those views.
//
// Visible = projects into the image in front of the camera AND is not behind the surface the view shows:
// its camera depth z must not exceed the rasterized median depth at its pixel by more than
// max(depth_tolerance * median, its own largest 1-sigma scale). Occluded Gaussians (the floor behind the
// object, the object's own far side) therefore cast no vote in that view; a Gaussian visible in no view is
// never selected by votes (the hull closure can still add it: see close_selection()). The visibility test is
// visible_centre_pixels (selection_region.h).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/io/camera.h"
#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/scene/selection_points.h"
#include "render/raster/raster_types.h"

namespace goris {

class GaussianModel;

// A view with its object mask: one channel at camera.width x camera.height, CPU, values in [0, 1].
struct MaskedView {
  std::string name;
  Camera camera;
  Image mask;
};

struct MaskVoteSettings {
  float mask_threshold = 0.5f;   // a mask pixel is "object" above this
  // Of the views where the Gaussian is visible. Below one half: the target's fringe (its blurred edge, the
  // Gaussians it shares with the surface at its foot) falls inside the masks in fewer than half of its views,
  // and left behind it tints the fill where the target stood. 0.35 raised the generalization suite's glossy mean
  // and its worst scene over 0.5 (docs/lab/2026-12-06-reflection-fitted-out-of-the-photos.md).
  float min_fraction = 0.35f;
  int min_views = 1;             // visible in at least this many views to be selected at all
  float depth_tolerance = 0.02f; // relative to the median depth (see above)
};

struct MaskVotes {
  SelectionMask selected;
  std::vector<std::uint16_t> visible;  // per Gaussian: masked views in which it is visible
  std::vector<std::uint16_t> inside;   // ... and inside the mask
  std::size_t views = 0;               // views that voted
};

// Rasterizes the model (on its own device, with `raster`) from every view for the median depth and counts
// the votes. Throws goris::Error for no views, a mask of the wrong size or channel count, or bad settings.
// `on_view` (optional) is told (views done, views) after each view, for progress display.
MaskVotes labels_from_masks(const GaussianModel& model, const std::vector<MaskedView>& views,
                            const MaskVoteSettings& settings = {}, const RasterSettings& raster = {},
                            const std::function<void(std::size_t, std::size_t)>& on_view = {});

// The object masks of `views` at their cameras' size: the data set's own (View::object_mask, mask_XXX.png)
// when mask_dir is empty, else DIR/mask_XXX.png for r_XXX, or DIR/<view name>.<png|jpg|...>. Views without
// a mask are skipped; no mask at all is a goris::Error that says where masks were looked for.
std::vector<MaskedView> load_masked_views(const std::vector<View>& views,
                                          const std::optional<std::filesystem::path>& mask_dir = std::nullopt);

}  // namespace goris
