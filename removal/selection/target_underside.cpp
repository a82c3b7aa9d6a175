#include "removal/selection/target_underside.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace goris {

SelectionMask target_underside(const std::vector<glm::vec3>& centres, const SelectionMask& target,
                               const SelectionMask& selected, const MirrorPlane& plane,
                               const UndersideSettings& settings) {
  const std::size_t n = centres.size();
  SelectionMask out(n, 0);
  if (!plane.found || target.size() != n || selected.size() != n) return out;
  const glm::dvec3 normal = plane.normal;
  auto in_plane = [&](const glm::vec3& p) {  // the centre projected onto the plane through the origin
    const glm::dvec3 d(p);
    return d - normal * glm::dot(normal, d);
  };
  glm::dvec3 centroid(0.0);
  double top = -std::numeric_limits<double>::infinity();
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (target[i]) {
      centroid += in_plane(centres[i]);
      top = std::max(top, plane.signed_distance(glm::dvec3(centres[i])));
      ++count;
    }
  if (count == 0) return out;
  centroid /= double(count);
  std::vector<double> radii;
  radii.reserve(count);
  for (std::size_t i = 0; i < n; ++i)
    if (target[i]) radii.push_back(glm::length(in_plane(centres[i]) - centroid));
  const std::size_t q = std::size_t(std::clamp(settings.radius_quantile, 0.0, 1.0) * double(count - 1));
  std::nth_element(radii.begin(), radii.begin() + long(q), radii.end());
  const double radius = settings.radius_ratio * radii[q];
  for (std::size_t i = 0; i < n; ++i) {
    if (target[i] || selected[i]) continue;
    const double h = plane.signed_distance(glm::dvec3(centres[i]));
    if (h > 0 && h < top && glm::length(in_plane(centres[i]) - centroid) < radius) out[i] = 1;
  }
  return out;
}

}  // namespace goris
