#pragma once
// A picture of a selection for people (goris select writes a few; the editor has its own GL overlay):
// the view rendered with the selected Gaussians tinted, beside the view rendered without them.
#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/io/image.h"
#include "core/scene/selection_points.h"
#include "render/raster/raster_types.h"

namespace goris {

class GaussianModel;

struct PreviewSettings {
  glm::vec3 tint{1.0f, 0.1f, 0.7f};
  float strength = 0.6f;  // tint blended in proportion to the selected Gaussians' rendered coverage
};

// RGB image of 2 * camera.width x camera.height on the CPU: left tinted, right with the selection removed.
// Rendered on the model's device. Throws goris::Error when the mask size differs from the model's.
Image render_selection_preview(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                               const RasterSettings& raster = {}, const PreviewSettings& settings = {});

}  // namespace goris
