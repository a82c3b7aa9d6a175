// Camera paths of `goris export` (export/frames/camera_path.h): the orbit rule recovers a ring of cameras'
// centre, up, radius and height; orbit frames look at the centre, are evenly spaced, counter-clockwise,
// upright; interpolated distillation cameras lie between neighbours with proper rotations.
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/util/error.h"
#include "export/frames/camera_path.h"
#include "tests/support/test_support.h"

using namespace goris;

namespace {

Camera intrinsics(int w, int h, float f) {
  return Camera{.width = w, .height = h, .fx = f, .fy = f, .cx = 0.5f * float(w), .cy = 0.5f * float(h)};
}

glm::vec3 camera_up(const Camera& c) { return -glm::vec3(c.R[0][1], c.R[1][1], c.R[2][1]); }
glm::vec3 camera_right(const Camera& c) { return glm::vec3(c.R[0][0], c.R[1][0], c.R[2][0]); }

void expect_rotation(const Camera& c) {
  const glm::mat3 I = c.R * glm::transpose(c.R);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(I[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
  EXPECT_NEAR(glm::determinant(c.R), 1.0f, 1e-5f);
}

// A ring of cameras at `height` above `center` (along `up`) and `radius` from the axis, looking at the
// centre, image up along `up`, starting at angle `phase`.
std::vector<Camera> ring(glm::vec3 center, glm::vec3 up, float radius, float height, int n, float phase) {
  up = glm::normalize(up);
  const glm::vec3 e1 = glm::normalize(glm::cross(up, std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const glm::vec3 e2 = glm::cross(up, e1);
  std::vector<Camera> cams;
  for (int k = 0; k < n; ++k) {
    const float a = phase + 6.2831853f * float(k) / float(n);
    const glm::vec3 eye = center + height * up + radius * (std::cos(a) * e1 + std::sin(a) * e2);
    cams.push_back(look_at_camera(intrinsics(40, 30, 35.0f), eye, center, up));
  }
  return cams;
}

}  // namespace

TEST(ExportCameraPath, LookAtCameraIsUprightAndCentred) {
  const glm::vec3 eye(3, -1, 2), target(0.2f, 0.1f, -0.3f), up(0, 0, 1);
  const Camera c = look_at_camera(intrinsics(64, 48, 50.0f), eye, target, up);
  expect_rotation(c);
  EXPECT_NEAR(glm::length(c.center() - eye), 0.0f, 1e-5f);
  const glm::vec2 p = c.project_camera(c.to_camera(target));
  EXPECT_NEAR(p.x, 32.0f, 1e-3f);
  EXPECT_NEAR(p.y, 24.0f, 1e-3f);
  EXPECT_GT(c.to_camera(target).z, 0.0f);
  EXPECT_NEAR(glm::dot(camera_right(c), up), 0.0f, 1e-5f);  // no roll
  EXPECT_GT(glm::dot(camera_up(c), up), 0.0f);              // not upside down
  // Looking straight along up still gives a proper rotation.
  const Camera down = look_at_camera(intrinsics(8, 8, 8.0f), glm::vec3(0, 0, 5), glm::vec3(0.0f), up);
  expect_rotation(down);
  EXPECT_NEAR(glm::dot(down.forward(), glm::vec3(0, 0, -1)), 1.0f, 1e-5f);
}

TEST(ExportCameraPath, OrbitRecoversTheRingOfCameras) {
  for (const glm::vec3 up : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f))}) {
    const glm::vec3 center(0.3f, -0.2f, 0.1f);
    const std::vector<Camera> cams = ring(center, up, 4.0f, 1.5f, 12, 0.3f);
    EXPECT_NEAR(glm::length(cameras_up(cams) - up), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(cameras_focus(cams) - center), 0.0f, 1e-4f);
    const OrbitPath p = orbit_from_cameras(cams);
    EXPECT_NEAR(glm::length(p.center - center), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(p.up - up), 0.0f, 1e-4f);
    EXPECT_NEAR(p.radius, 4.0f, 1e-3f);
    EXPECT_NEAR(p.height, 1.5f, 1e-3f);
    EXPECT_EQ(p.intrinsics.width, 40);
    // Frame 0 starts where the first camera is.
    EXPECT_NEAR(glm::length(orbit_eye(p, 0, 7) - cams[0].center()), 0.0f, 1e-3f);
  }
}

TEST(ExportCameraPath, OrbitFramesLookAtTheCentreEvenlySpacedCounterClockwise) {
  const glm::vec3 center(1, 2, -0.5f), up(0, 0, 1);
  const OrbitPath p = orbit_from_cameras(ring(center, up, 3.0f, 2.0f, 9, 1.0f));
  for (int n : {1, 4, 36}) {
    const std::vector<Camera> cams = orbit_cameras(p, n);
    ASSERT_EQ(cams.size(), size_t(n));
    for (int k = 0; k < n; ++k) {
      const Camera& c = cams[size_t(k)];
      expect_rotation(c);
      EXPECT_EQ(c.width, 40);
      EXPECT_EQ(c.height, 30);
      // Looks at the centre: it projects to the principal point, in front of the camera.
      const glm::vec3 pc = c.to_camera(p.center);
      EXPECT_GT(pc.z, 0.0f);
      const glm::vec2 px = c.project_camera(pc);
      EXPECT_NEAR(px.x, c.cx, 1e-3f);
      EXPECT_NEAR(px.y, c.cy, 1e-3f);
      // Upright: no roll, image up towards world up.
      EXPECT_NEAR(glm::dot(camera_right(c), up), 0.0f, 1e-5f);
      EXPECT_GT(glm::dot(camera_up(c), up), 0.0f);
      // On the circle: the cameras' height and distance from the axis.
      const glm::vec3 d = c.center() - p.center;
      EXPECT_NEAR(glm::dot(d, up), 2.0f, 1e-3f);
      EXPECT_NEAR(glm::length(d - glm::dot(d, up) * up), 3.0f, 1e-3f);
      if (n < 2) continue;
      // Evenly spaced and turning counter-clockwise about up.
      const glm::vec3 a = cams[size_t(k)].center() - p.center, b = cams[size_t((k + 1) % n)].center() - p.center;
      const glm::vec3 ha = glm::normalize(a - glm::dot(a, up) * up), hb = glm::normalize(b - glm::dot(b, up) * up);
      const float angle = std::atan2(glm::dot(glm::cross(ha, hb), up), glm::dot(ha, hb));
      EXPECT_NEAR(angle, 6.2831853f / float(n), 1e-3f) << "frame " << k << " of " << n;
    }
  }
}

TEST(ExportCameraPath, BadInput) {
  EXPECT_THROW(orbit_from_cameras({}), Error);
  EXPECT_THROW(cameras_focus({}), Error);
  const OrbitPath p = orbit_from_cameras(ring(glm::vec3(0.0f), glm::vec3(0, 0, 1), 2, 1, 4, 0));
  EXPECT_THROW(orbit_cameras(p, 0), Error);
  // Two cameras above the same point looking down with opposite image-up directions: no mean up (falls back
  // to +z), and both sit on the vertical axis through their focus -> no circle.
  Camera a = look_at_camera(intrinsics(8, 8, 8), glm::vec3(0, 0, 4), glm::vec3(0.0f), glm::vec3(0, 1, 0));
  Camera b = look_at_camera(intrinsics(8, 8, 8), glm::vec3(0, 0, 4), glm::vec3(0.0f), glm::vec3(0, -1, 0));
  try {
    orbit_from_cameras({a, b});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no circle"), std::string::npos) << e.what();
  }
}

TEST(ExportCameraPath, InterpolatedCamerasLieBetweenNeighbours) {
  const std::vector<Camera> cams = ring(glm::vec3(0.0f), glm::vec3(0, 0, 1), 4.0f, 1.0f, 10, 0.0f);
  const std::vector<Camera> between = interpolated_cameras(cams, 25, 7);
  ASSERT_EQ(between.size(), 25u);
  const float spacing = glm::length(cams[0].center() - cams[1].center());
  for (size_t j = 0; j < between.size(); ++j) {
    const Camera& c = between[j];
    expect_rotation(c);
    const Camera& a = cams[j % cams.size()];
    const float from_a = glm::length(c.center() - a.center());
    // Between a and one of its 3 nearest neighbours (on this ring: at most 2 steps away), a quarter to
    // three quarters of the way.
    EXPECT_GT(from_a, 0.2f * spacing);
    EXPECT_LT(from_a, 0.8f * 2.0f * spacing);
    // Still looking roughly at the ring's centre (slerp between two inward-looking cameras).
    EXPECT_GT(glm::dot(c.forward(), glm::normalize(-c.center())), 0.95f);
    EXPECT_EQ(c.width, a.width);
  }
  // Deterministic for a seed, different for another.
  const std::vector<Camera> again = interpolated_cameras(cams, 25, 7), other = interpolated_cameras(cams, 25, 8);
  EXPECT_EQ(again[3].t, between[3].t);
  bool differs = false;
  for (size_t j = 0; j < other.size(); ++j) differs |= other[j].t != between[j].t;
  EXPECT_TRUE(differs);
  EXPECT_TRUE(interpolated_cameras({cams[0]}, 5, 1).empty());
  EXPECT_TRUE(interpolated_cameras(cams, 0, 1).empty());
}

TEST(ExportCameraPath, EvenlySpaced) {
  EXPECT_EQ(evenly_spaced(10, 0), (std::vector<size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(evenly_spaced(10, 4), (std::vector<size_t>{0, 2, 5, 7}));
  EXPECT_EQ(evenly_spaced(3, 8), (std::vector<size_t>{0, 1, 2}));
  EXPECT_TRUE(evenly_spaced(0, 3).empty());
}
