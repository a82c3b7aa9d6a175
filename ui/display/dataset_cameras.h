#pragma once
// Facts the viewport camera needs from a data set's cameras: which way is up, and which training camera is
// nearest to the current view (for the side-by-side / slider comparison with the input photo).
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "core/io/camera.h"
#include "core/io/dataset.h"

namespace goris::ui {

// The mean of the cameras' "up" directions (-y of OpenCV axes), normalised; +z when there are none or they
// cancel out.
glm::vec3 world_up(const std::vector<View>& views);

// Index of the view whose camera is closest to `cam`: distance between centres (relative to `scale`) plus
// the angle between viewing directions (radians); nullopt when `views` is empty.
std::optional<size_t> nearest_view(const std::vector<View>& views, const Camera& cam, float scale);

}  // namespace goris::ui
