// The editor's view camera maths (ui/display/orbit_camera.h, ui/display/dataset_cameras.h): the cameras it
// builds follow the engine's convention (core/io/camera.h), every control moves the view the way its name
// says, and snapping to a data set camera reproduces that camera exactly.
#include <cmath>
#include <glm/gtc/matrix_access.hpp>
#include <random>

#include "tests/support/test_support.h"
#include "ui/display/dataset_cameras.h"
#include "ui/display/orbit_camera.h"

using namespace goris;
using namespace goris::ui;

namespace {

void expect_near(const glm::vec3& a, const glm::vec3& b, float tol, const char* what) {
  EXPECT_NEAR(glm::length(a - b), 0.0f, tol)
      << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

// A camera at `eye` looking at `at` with `up` roughly up, OpenCV axes.
Camera look_at(glm::vec3 eye, glm::vec3 at, glm::vec3 up, int w, int h, float f) {
  Camera c;
  c.width = w;
  c.height = h;
  c.fx = c.fy = f;
  c.cx = 0.5f * float(w);
  c.cy = 0.5f * float(h);
  const glm::vec3 z = glm::normalize(at - eye), x = glm::normalize(glm::cross(z, up)), y = glm::cross(z, x);
  for (int k = 0; k < 3; ++k) {
    c.R[k][0] = x[k];
    c.R[k][1] = y[k];
    c.R[k][2] = z[k];
  }
  c.t = -(c.R * eye);
  return c;
}

OrbitCamera z_up_scene() {
  OrbitCamera o;
  o.set_world({0, 0, 1}, {0.5f, -0.25f, 0.1f}, 2.0f);
  return o;
}

}  // namespace

TEST(StudioOrbitCamera, BuildsEngineCameras) {
  OrbitCamera o = z_up_scene();
  o.orbit(0.7f, 0.2f);
  const Camera c = o.camera(320, 200);
  EXPECT_EQ(c.width, 320);
  EXPECT_EQ(c.height, 200);
  EXPECT_NEAR(c.fx, c.fy, 1e-4f);
  EXPECT_NEAR(2.0f * std::atan(100.0f / c.fy), o.fov_y(), 1e-5f);
  // R is a rotation; the eye is the camera centre; the target is straight ahead (image centre).
  EXPECT_NEAR(glm::determinant(c.R), 1.0f, 1e-5f);
  const glm::mat3 rrt = c.R * glm::transpose(c.R);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(rrt[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
  expect_near(c.center(), o.eye(), 1e-4f, "centre");
  expect_near(c.forward(), o.forward(), 1e-5f, "forward");
  const glm::vec3 t = c.to_camera(o.target());
  EXPECT_NEAR(t.z, o.distance(), 1e-4f);
  const glm::vec2 px = c.project_camera(t);
  EXPECT_NEAR(px.x, 160.0f, 1e-3f);
  EXPECT_NEAR(px.y, 100.0f, 1e-3f);
  // World up appears upwards in the image (OpenCV: smaller v).
  const glm::vec2 above = c.project_camera(c.to_camera(o.target() + glm::vec3(0, 0, 0.1f)));
  EXPECT_LT(above.y, 100.0f);
  EXPECT_NEAR(above.x, 160.0f, 1e-2f);
}

TEST(StudioOrbitCamera, ControlsMoveTheViewAsNamed) {
  OrbitCamera o = z_up_scene();
  const glm::vec3 target = o.target();
  const float d = o.distance();
  // Orbit: same target and distance, another direction; the pitch stays below the pole.
  const glm::vec3 eye0 = o.eye();
  o.orbit(0.5f, 0.3f);
  expect_near(o.target(), target, 1e-6f, "orbit target");
  EXPECT_NEAR(glm::length(o.eye() - target), d, 1e-4f);
  EXPECT_GT(glm::length(o.eye() - eye0), 0.1f);
  o.orbit(0.0f, 10.0f);
  EXPECT_LT(o.pitch(), 1.5708f);
  EXPECT_GT(glm::dot(o.forward(), glm::vec3(0, 0, -1)), 0.99f);  // looking almost straight down
  o.orbit(0.0f, -20.0f);
  EXPECT_GT(o.pitch(), -1.5708f);
  o.orbit(0.0f, 10.0f - 0.3f);

  // Pan right by a tenth of the view: the old target now projects left of the centre.
  Camera before = o.camera(200, 200);
  o.pan(0.1f, 0.0f);
  Camera after = o.camera(200, 200);
  const glm::vec2 old_target = after.project_camera(after.to_camera(target));
  EXPECT_NEAR(old_target.x, 100.0f - 20.0f, 0.5f);
  EXPECT_NEAR(old_target.y, 100.0f, 0.5f);
  expect_near(after.forward(), before.forward(), 1e-6f, "pan keeps the direction");
  // Pan down: the old point moves up in the image.
  o.pan(-0.1f, 0.1f);
  const Camera down = o.camera(200, 200);
  EXPECT_NEAR(down.project_camera(down.to_camera(target)).y, 100.0f - 20.0f, 0.5f);

  // Zoom: closer by 0.9^steps, clamped to the scene's scale.
  const float d1 = o.distance();
  o.zoom(2.0f);
  EXPECT_NEAR(o.distance(), d1 * 0.81f, 1e-5f);
  o.zoom(1000.0f);
  EXPECT_GT(o.distance(), 0.0f);

  // Fly: eye and target move together along the view, screen right and world up.
  const glm::vec3 e = o.eye(), f = o.forward();
  o.fly(0.3f, 0.0f, 0.0f);
  expect_near(o.eye(), e + 0.3f * f, 1e-5f, "fly forward");
  const Camera c = o.camera(100, 100);
  const glm::vec3 right = glm::vec3(c.R[0][0], c.R[1][0], c.R[2][0]);
  const glm::vec3 e2 = o.eye();
  o.fly(0.0f, 0.2f, 0.1f);
  expect_near(o.eye(), e2 + 0.2f * right + glm::vec3(0, 0, 0.1f), 1e-5f, "fly right and up");

  // Look (from a moderate pitch): the eye stays; looking right turns the view towards screen right,
  // looking up towards world up.
  o = z_up_scene();
  const Camera level = o.camera(100, 100);
  const glm::vec3 level_right = glm::vec3(level.R[0][0], level.R[1][0], level.R[2][0]);
  const glm::vec3 e3 = o.eye(), f3 = o.forward();
  o.look(0.1f, 0.0f);
  expect_near(o.eye(), e3, 1e-4f, "look keeps the eye");
  EXPECT_GT(glm::dot(o.forward() - f3, level_right), 0.05f);
  const float up_before = o.forward().z;
  o.look(0.0f, 0.1f);
  EXPECT_GT(o.forward().z, up_before + 0.05f);
}

TEST(StudioOrbitCamera, SnapReproducesDataSetCameras) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  for (glm::vec3 up : {glm::vec3(0, 0, 1), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(0.2f, 1, 0.1f))}) {
    for (int k = 0; k < 10; ++k) {
      OrbitCamera o;
      o.set_world(up, {0, 0, 0}, 1.5f);
      const glm::vec3 eye = glm::vec3(u(rng), u(rng), u(rng)) * 3.0f + up * 1.0f;
      const glm::vec3 at = glm::vec3(u(rng), u(rng), u(rng)) * 0.3f;
      const Camera cam = look_at(eye, at, up, 160, 120, 140.0f);
      o.snap_to(cam);
      const Camera back = o.camera(160, 120);
      EXPECT_NEAR(o.fov_y(), 2.0f * std::atan(60.0f / 140.0f), 1e-5f);
      EXPECT_NEAR(back.fy, 140.0f, 1e-2f);
      for (int i = 0; i < 3; ++i) expect_near(glm::row(back.R, i), glm::row(cam.R, i), 2e-4f, "rotation row");
      expect_near(back.center(), cam.center(), 1e-4f, "centre");
    }
  }
}

TEST(StudioOrbitCamera, DataSetCameraFacts) {
  // Cameras around a z-up scene, looking at the origin: up is +z, the nearest camera is found.
  std::vector<View> views;
  for (int i = 0; i < 8; ++i) {
    const float a = float(i) * 0.785398f;
    View v;
    v.name = "r_" + std::to_string(i);
    v.camera = look_at({4 * std::cos(a), 4 * std::sin(a), 1.5f}, {0, 0, 0}, {0, 0, 1}, 64, 64, 60.0f);
    views.push_back(v);
  }
  const glm::vec3 up = world_up(views);
  EXPECT_GT(up.z, 0.9f);
  EXPECT_NEAR(glm::length(up), 1.0f, 1e-5f);
  EXPECT_EQ(world_up({}), glm::vec3(0, 0, 1));
  const Camera near3 =
      look_at(views[3].camera.center() * 1.1f + glm::vec3(0, 0, 0.1f), {0, 0, 0}, {0, 0, 1}, 64, 64, 60.0f);
  EXPECT_EQ(nearest_view(views, near3, 4.0f), 3u);
  EXPECT_EQ(nearest_view(views, views[6].camera, 4.0f), 6u);
  EXPECT_FALSE(nearest_view({}, near3, 4.0f).has_value());
}
