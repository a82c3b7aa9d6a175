// The mirror-world plane of --mode auto (train/setup/mirror_world_detection.h): a table whose geometry behind it
// copies the balls on it is found (level or tilted); a Lambertian table, floaters under one and a copy seen
// from both sides are not.
#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "train/setup/mirror_world_detection.h"

using namespace goris;

namespace {

// A table top (the plane through `origin` with normal `up`, a disc of radius 1.5), three balls standing on it,
// and cameras on a ring above it. mirror: the balls reflected through the plane too, as a radiance model
// shows a mirror's reflections.
struct Scene {
  std::vector<glm::vec3> points, cameras;
};

Scene table(const glm::vec3& up, const glm::vec3& origin, bool mirror, bool cameras_below_too = false) {
  Scene s;
  const glm::vec3 a = std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 e1 = glm::normalize(glm::cross(up, a)), e2 = glm::cross(up, e1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int k = 0; k < 3000; ++k) {  // the table top
    const float x = 1.5f * u(rng), y = 1.5f * u(rng);
    if (x * x + y * y <= 2.25f) s.points.push_back(origin + x * e1 + y * e2);
  }
  const glm::vec2 feet[3] = {{0.4f, 0.2f}, {-0.5f, 0.3f}, {0.1f, -0.6f}};
  for (const glm::vec2& f : feet)
    for (int k = 0; k < 700; ++k) {  // a ball of radius 0.2 on the table: its surface
      glm::vec3 d(u(rng), u(rng), u(rng));
      if (!(glm::length(d) > 0.1f)) continue;
      d = glm::normalize(d);
      const float h = 0.2f + 0.2f * glm::dot(d, glm::vec3(0, 0, 1));
      const glm::vec3 p = origin + f.x * e1 + f.y * e2 + h * up + 0.2f * (d.x * e1 + d.y * e2);
      s.points.push_back(p);
      if (mirror) s.points.push_back(p - 2.0f * glm::dot(p - origin, up) * up);
    }
  for (int k = 0; k < 24; ++k) {
    const float t = 6.2831853f * float(k) / 24.0f;
    const float h = cameras_below_too && k % 2 ? -2.0f : 2.0f;
    s.cameras.push_back(origin + 4.0f * (std::cos(t) * e1 + std::sin(t) * e2) + h * up);
  }
  return s;
}

}  // namespace

TEST(MirrorWorldPlane, FoundWhereTheGeometryBehindAPlaneMirrorsWhatStandsOnIt) {
  const Scene s = table({0, 0, 1}, {0, 0, 0.3f}, true);
  const MirrorWorldPlane mw = find_mirror_world_plane(s.points, s.cameras);
  EXPECT_TRUE(mw.found) << mw.summary;
  EXPECT_GT(glm::dot(mw.normal, glm::vec3(0, 0, 1)), std::cos(glm::radians(4.0f))) << mw.summary;
  EXPECT_NEAR(mw.height, 0.3f, 0.1f) << mw.summary;
  EXPECT_GT(mw.mirrored, mw.behind / 2) << mw.summary;
}

TEST(MirrorWorldPlane, FoundOnATiltedPlane) {
  const glm::vec3 up = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));
  const Scene s = table(up, {0.2f, -0.1f, 0.0f}, true);
  const MirrorWorldPlane mw = find_mirror_world_plane(s.points, s.cameras);
  EXPECT_TRUE(mw.found) << mw.summary;
  EXPECT_GT(glm::dot(mw.normal, up), std::cos(glm::radians(4.0f))) << mw.summary;
}

TEST(MirrorWorldPlane, NoneOnALambertianTable) {
  const Scene s = table({0, 0, 1}, {0, 0, 0}, false);
  const MirrorWorldPlane mw = find_mirror_world_plane(s.points, s.cameras);
  EXPECT_FALSE(mw.found) << mw.summary;
}

TEST(MirrorWorldPlane, NoneWhenWhatLiesBehindThePlaneCopiesNothing) {
  // Floaters under a Lambertian table (a short run's fog), a fifth as many as the table's points.
  Scene s = table({0, 0, 1}, {0, 0, 0}, false);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int k = 0; k < 600; ++k) s.points.push_back({1.2f * u(rng), 1.2f * u(rng), -0.05f - 0.6f * std::abs(u(rng))});
  const MirrorWorldPlane mw = find_mirror_world_plane(s.points, s.cameras);
  EXPECT_FALSE(mw.found) << mw.summary;
}

TEST(MirrorWorldPlane, NoneWhenCamerasLookFromBothSides) {
  // A mirrored copy seen from above and below is an object's own symmetry, not a mirror's reflection.
  const Scene s = table({0, 0, 1}, {0, 0, 0}, true, /*cameras_below_too=*/true);
  const MirrorWorldPlane mw = find_mirror_world_plane(s.points, s.cameras);
  EXPECT_FALSE(mw.found) << mw.summary;
}

TEST(MirrorWorldPlane, TooFewPointsSayNothing) {
  const MirrorWorldPlane mw = find_mirror_world_plane({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 5}});
  EXPECT_FALSE(mw.found);
  EXPECT_FALSE(mw.summary.empty());
}
