#pragma once
// Reference views of stage 2 (the paper's S1.4 after 3DGIC: the three views with the
// largest inpainting masks), here also required to see the hole from different directions, and the
// maps of the removed scene that get inpainted in them.
//
// The rule (choose_reference_views):
//   Candidates are the views whose inpainting mask has at least min_pixels pixels, sorted by mask area,
//   largest first (ties: lower view index first). d_v is the unit direction from view v's camera centre
//   to the hole centroid. Going down the list, a view is accepted when the angle between its d_v and
//   the d of every view accepted so far is at least the threshold (min_angle_deg, 20 degrees by
//   default), until `count` (3) views are accepted. When the list runs out first, the threshold is
//   halved and the pass repeated over the views not yet accepted (keeping those accepted), down to
//   below 1 degree, after which the largest remaining views are taken regardless of angle. Fewer
//   candidates than `count`: all of them. No candidate: no reference view (nothing to inpaint).
//   Deterministic for the same masks and cameras.
//
// The hole centroid (hole_centroid) is the per-axis median of the world points behind every masked
// pixel of every view: the removed surface where there is one, else the target's own depth.
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/inpaint/map_set.h"
#include "core/io/camera.h"
#include "removal/masks/inpaint_mask.h"
#include "render/raster/raster_types.h"

namespace goris {

class GaussianModel;

struct ReferenceViewSettings {
  int count = 3;
  float min_angle_deg = 20.0f;
  std::size_t min_pixels = 1;
};

struct ReferenceChoice {
  std::vector<int> views;               // in the order accepted (largest mask first)
  std::vector<float> angle_threshold;   // per chosen view: the threshold in force when it was accepted
                                        // (degrees; 0 = taken regardless of angle)
};

// The rule above. mask_pixels[v] and camera_centers[v] per view (same length, else goris::Error).
ReferenceChoice choose_reference_views(const std::vector<std::size_t>& mask_pixels,
                                       const std::vector<glm::vec3>& camera_centers, const glm::vec3& hole_center,
                                       const ReferenceViewSettings& settings = {});

// The same from inpainting masks (stats.masked) and their cameras, with the hole centroid computed
// here. Empty when no mask has min_pixels pixels.
ReferenceChoice choose_reference_views(const std::vector<InpaintMaskView>& masks, const std::vector<Camera>& cameras,
                                       const ReferenceViewSettings& settings = {});

// Per-axis median of the world points behind the masked pixels (see above); nullopt when no view has a
// masked pixel with a depth.
std::optional<glm::vec3> hole_centroid(const std::vector<InpaintMaskView>& masks, const std::vector<Camera>& cameras);

// The removed scene's maps for one view, ready for inpainting: rgb (the rasterized colour over
// settings.background), depth (depth / alpha, 0 where alpha <= min_alpha), normal (camera space,
// normalised; 0 where alpha <= min_alpha) and the materials diffuse, fresnel, roughness, region
// (alpha-weighted sums of the activated extras divided by alpha; 0 where alpha <= min_alpha). Rendered on the
// model's device; the maps come back on the CPU. In the shading modes the caller may replace `rgb` by the
// shaded image.
MapSet render_removed_maps(GaussianModel& kept, const Camera& camera, const RasterSettings& settings,
                           float min_alpha = 0.5f);

}  // namespace goris
