#include "removal/selection/selection_region.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/selection/select_view.h"
#include "render/raster/rasterizer.h"

namespace goris {

std::vector<std::int32_t> visible_centre_pixels(const GaussianModel& model, const std::vector<glm::vec3>& positions,
                                                const std::vector<float>& max_scales, const Camera& cam,
                                                const RasterSettings& raster, float depth_tolerance) {
  const std::size_t n = model.count();
  if (positions.size() != n || max_scales.size() != n)
    throw Error("visibility", "centres and scales of " + std::to_string(positions.size()) + " Gaussians for a model of " +
                                  std::to_string(n));
  std::vector<std::int32_t> px = centre_pixels(positions, cam, raster.near_plane);
  if (n == 0) return px;
  const RasterOutput out = rasterize(plain_gaussian_view(model), cam, raster, model.device());
  const std::vector<float> median = out.gbuffer.median_depth.to_host();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (px[i] < 0) continue;
      const float z = cam.to_camera(positions[i]).z;
      const float md = median[std::size_t(px[i])];
      // md == 0: nothing was rendered at this pixel, so nothing hides the centre either.
      const bool visible = md <= 0.0f || z <= md + std::max(depth_tolerance * md, max_scales[i]);
      if (!visible) px[i] = -1;
    }
  });
  return px;
}

SelectionMask select_in_view_region(const GaussianModel& model, const SelectionPoints& pts, const Camera& camera,
                                    const ScreenPolygon& polygon, Through through, const RasterSettings& raster) {
  if (pts.size() != model.count())
    throw Error("selection", "points of " + std::to_string(pts.size()) + " Gaussians for a model of " +
                                 std::to_string(model.count()));
  if (through == Through::All) return select_in_polygon(pts.position, camera, polygon, raster.near_plane);
  const std::vector<std::int32_t> px = visible_centre_pixels(model, pts.position, pts.scale, camera, raster);
  std::vector<std::uint8_t> visible(px.size());
  for (std::size_t i = 0; i < px.size(); ++i) visible[i] = px[i] >= 0;
  return select_in_polygon(pts.position, camera, polygon, raster.near_plane, &visible);
}

}  // namespace goris
