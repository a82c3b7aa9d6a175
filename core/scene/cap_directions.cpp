#include "core/scene/cap_directions.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace goris {

std::vector<glm::dvec3> cap_directions(const glm::dvec3& axis, double radius, int n) {
  if (n <= 1 || radius <= 0.0) return {axis};
  const double golden_angle = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  const glm::dvec3 helper = std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, axis));
  const glm::dvec3 b = glm::cross(axis, t);
  const double one_minus_cos = 1.0 - std::cos(radius);
  std::vector<glm::dvec3> out(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double cos_t = 1.0 - (k + 0.5) / n * one_minus_cos;
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    const double phi = k * golden_angle;
    out[std::size_t(k)] = glm::normalize(cos_t * axis + sin_t * (std::cos(phi) * t + std::sin(phi) * b));
  }
  return out;
}

}  // namespace goris
