#pragma once
// Which Gaussians a view shows, and screen-space selection through the depth (removal/selection/
// selection_screen.h has the geometry).
//
// A centre is visible in a view when it projects into the image in front of the camera and is not behind
// the surface the view shows: its camera depth z does not exceed the rasterized median depth at its pixel
// by more than max(depth_tolerance * median, its own largest 1-sigma scale). The object masks' votes
// (selection_masks.h) use the same test.
#include <cstdint>
#include <vector>

#include "core/io/camera.h"
#include "core/scene/selection_points.h"
#include "removal/selection/selection_screen.h"
#include "render/raster/raster_types.h"

namespace goris {

class GaussianModel;

constexpr float kVisibleDepthTolerance = 0.02f;

// Per Gaussian the pixel its visible centre lies on (y * width + x), or -1 when it is not visible.
// `positions` and `max_scales` are the model's centres and largest 1-sigma scales (selection_points).
// Rasterizes the model once on its own device.
std::vector<std::int32_t> visible_centre_pixels(const GaussianModel& model, const std::vector<glm::vec3>& positions,
                                                const std::vector<float>& max_scales, const Camera& camera,
                                                const RasterSettings& raster = {},
                                                float depth_tolerance = kVisibleDepthTolerance);

// The Gaussians whose centre projects inside `polygon`: through the depth (Through::Visible, the centres
// visible_centre_pixels finds) or through everything (Through::All, every centre in front of the camera).
SelectionMask select_in_view_region(const GaussianModel& model, const SelectionPoints& pts, const Camera& camera,
                                    const ScreenPolygon& polygon, Through through, const RasterSettings& raster = {});

}  // namespace goris
