#include "ui/display/dataset_cameras.h"

#include <algorithm>
#include <cmath>

namespace goris::ui {

glm::vec3 world_up(const std::vector<View>& views) {
  glm::vec3 sum(0.0f);
  for (const View& v : views) {
    const glm::mat3& R = v.camera.R;
    sum -= glm::vec3(R[0][1], R[1][1], R[2][1]);  // row 1 of R is the camera's "down" in world space
  }
  const float len = glm::length(sum);
  return len > 1e-3f * float(std::max<size_t>(views.size(), 1)) ? sum / len : glm::vec3(0, 0, 1);
}

std::optional<size_t> nearest_view(const std::vector<View>& views, const Camera& cam, float scale) {
  if (views.empty()) return std::nullopt;
  const glm::vec3 c = cam.center(), f = glm::normalize(cam.forward());
  const float s = scale > 0 ? scale : 1.0f;
  size_t best = 0;
  float best_cost = INFINITY;
  for (size_t i = 0; i < views.size(); ++i) {
    const Camera& v = views[i].camera;
    const float angle = std::acos(std::clamp(glm::dot(glm::normalize(v.forward()), f), -1.0f, 1.0f));
    const float cost = glm::length(v.center() - c) / s + angle;
    if (cost < best_cost) {
      best_cost = cost;
      best = i;
    }
  }
  return best;
}

}  // namespace goris::ui
