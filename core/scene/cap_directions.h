#pragma once
// Directions spread evenly over a spherical cap (a Fibonacci spiral): light directions round a guess,
// plane normals round the side the cameras look from.
#include <vector>

#include <glm/glm.hpp>

namespace goris {

// n unit directions within `radius` radians of the unit `axis`, evenly spread (equal areas); {axis} when
// n <= 1 or radius <= 0. Deterministic.
std::vector<glm::dvec3> cap_directions(const glm::dvec3& axis, double radius, int n);

}  // namespace goris
