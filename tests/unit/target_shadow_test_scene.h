#pragma once
// The scene both target-shadow test files use: a ball-shaped target above the floor z = 0, a tilted light and
// its shadow's strength per channel, and an analytic ray-ball occluder.
#include <cmath>
#include <random>

#include <glm/glm.hpp>

namespace goris {
namespace shadow_test {

const glm::vec3 kBall(0.0f, 0.0f, 0.5f);
constexpr float kBallRadius = 0.3f;
const glm::dvec3 kLight = glm::normalize(glm::dvec3(0.5, -0.3, 1.0));
const glm::dvec3 kStrength(0.6, 0.55, 0.45);

inline bool hits_ball(const glm::vec3& o, const glm::vec3& d) {
  const glm::vec3 oc = o - kBall;
  const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - kBallRadius * kBallRadius;
  const float disc = b * b - c;
  return disc > 0 && -b + std::sqrt(disc) > 0;
}

// A uniform random point in the unit ball (rejection sampling).
inline glm::vec3 in_unit_ball(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1);
  glm::vec3 d;
  do d = {u(rng), u(rng), u(rng)};
  while (glm::length(d) > 1.0f);
  return d;
}

}  // namespace shadow_test
}  // namespace goris
