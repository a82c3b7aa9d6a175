// Each loader's cameras follow core/io/camera.h: a known world point projects where it must.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/io/dataset.h"
#include "tests/support/test_support.h"
#include "tests/unit/colmap_test_writer.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
namespace fs = std::filesystem;

glm::vec2 project(const Camera& c, glm::vec3 world) { return c.project_camera(c.to_camera(world)); }

void expect_near(glm::vec2 a, glm::vec2 b, float tol = 1e-3f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
}

// Blender camera at (0, -4, 0) looking at the origin along +y, its up axis = world +z.
const nlohmann::json kBlenderFront = {
    {1, 0, 0, 0}, {0, 0, -1, -4}, {0, 1, 0, 0}, {0, 0, 0, 1}};

TEST(Camera, NerfSyntheticBlenderAxes) {
  const auto dir = test::scratch_dir("camera_nerf");
  nlohmann::json j;
  j["camera_angle_x"] = 2 * std::atan(0.5);  // fx = 0.5 * 80 / 0.5 = 80
  j["frames"] = {{{"file_path", "./train/r_0"}, {"transform_matrix", kBlenderFront}}};
  test::write_text(dir / "transforms_train.json", j.dump());
  test::write_png(dir / "train/r_0.png", 80, 60, 4);
  const Dataset d = load_dataset(dir);
  ASSERT_EQ(d.train.size(), 1u);
  const Camera& c = d.train[0].camera;
  EXPECT_FLOAT_EQ(c.fx, 80);
  EXPECT_FLOAT_EQ(c.fy, 80);
  EXPECT_FLOAT_EQ(c.cx, 40);
  EXPECT_FLOAT_EQ(c.cy, 30);
  EXPECT_NEAR(glm::length(c.center() - glm::vec3(0, -4, 0)), 0, 1e-6);
  EXPECT_NEAR(glm::length(c.forward() - glm::vec3(0, 1, 0)), 0, 1e-6);
  expect_near(project(c, {0, 0, 0}), {40, 30});
  expect_near(project(c, {1, 0, 0}), {60, 30});  // world +x is to the right
  expect_near(project(c, {0, 0, 1}), {40, 10});  // world up (+z in Blender) is up in the image (smaller v)
  EXPECT_GT(c.to_camera({0, 0, 0}).z, 0);        // in front of the camera
}

TEST(Camera, InstantNgpIntrinsicsAndPose) {
  const auto dir = test::scratch_dir("camera_ngp");
  nlohmann::json j;
  j.update({{"fl_x", 100.0}, {"fl_y", 110.0}, {"cx", 35.0}, {"cy", 28.0}, {"w", 80}, {"h", 60}, {"k1", 0.1}, {"p2", -0.01}});
  j["frames"] = {{{"file_path", "images/a.png"}, {"transform_matrix", kBlenderFront}}};
  test::write_text(dir / "transforms.json", j.dump());
  test::write_png(dir / "images/a.png", 80, 60);
  DatasetOptions o;
  o.test_every = 0;
  const Dataset d = load_dataset(dir / "transforms.json", o);
  ASSERT_EQ(d.train.size(), 1u);
  const Camera& c = d.train[0].camera;
  expect_near(project(c, {0, 0, 0}), {35, 28});
  expect_near(project(c, {1, 0, 0}), {35 + 25, 28});
  expect_near(project(c, {0, 0, 1}), {35, 28 - 27.5f});
  EXPECT_FLOAT_EQ(c.dist.k1, 0.1f);
  EXPECT_FLOAT_EQ(c.dist.p2, -0.01f);
  EXPECT_TRUE(c.has_distortion());
}

TEST(Camera, ColmapWorldToCamera) {
  const auto dir = test::scratch_dir("camera_colmap");
  ColmapSparseModel m;
  m.cameras = {test::colmap_camera(1, ColmapModel::Pinhole, 100, 80, {100, 120, 50, 40})};
  // 90 degrees about +y: R = [[0,0,1],[0,1,0],[-1,0,0]], t = (0, 0, 5).
  const double s = std::sqrt(0.5);
  m.images = {test::colmap_image(1, 1, "a.png", {s, 0, s, 0}, {0, 0, 5})};
  for (bool binary : {false, true}) {
    fs::remove_all(dir / "sparse");
    test::write_colmap_model(dir / "sparse/0", m, binary);
    test::write_png(dir / "images/a.png", 100, 80);
    DatasetOptions o;
    o.test_every = 0;
    const Dataset d = load_dataset(dir, o);
    ASSERT_EQ(d.train.size(), 1u);
    const Camera& c = d.train[0].camera;
    // (1, 2, 3) -> R p + t = (3, 2, -1) + (0, 0, 5) = (3, 2, 4) -> (100 * 3/4 + 50, 120 * 2/4 + 40).
    const glm::vec3 pc = c.to_camera({1, 2, 3});
    EXPECT_NEAR(pc.x, 3, 1e-5);
    EXPECT_NEAR(pc.y, 2, 1e-5);
    EXPECT_NEAR(pc.z, 4, 1e-5);
    expect_near(project(c, {1, 2, 3}), {125, 100});
  }
}

TEST(Camera, LlffAxesAndFocalScaling) {
  const auto dir = test::scratch_dir("camera_llff");
  // OpenCV identity rotation at centre (0, 0, -5): LLFF columns down = +y, right = +x, back = -z;
  // hwf for 300x400 originals with f = 500, images are 40x30 (scale 0.1 -> f = 50).
  std::vector<double> row = {0, 1, 0, 0, 300,  //
                             1, 0, 0, 0, 400,  //
                             0, 0, -1, -5, 500, 1.0, 10.0};
  test::write_bytes(dir / "poses_bounds.npy", test::npy_bytes({1, 17}, row));
  test::write_png(dir / "images/IMG_0.png", 40, 30);
  DatasetOptions o;
  o.test_every = 0;
  const Dataset d = load_dataset(dir, o);
  ASSERT_EQ(d.train.size(), 1u);
  const Camera& c = d.train[0].camera;
  EXPECT_FLOAT_EQ(c.fx, 50);
  EXPECT_FLOAT_EQ(c.cx, 20);
  EXPECT_FLOAT_EQ(c.cy, 15);
  expect_near(project(c, {1, 2, 0}), {30, 35});
  EXPECT_NEAR(glm::length(c.center() - glm::vec3(0, 0, -5)), 0, 1e-6);
  ASSERT_TRUE(d.depth_range.has_value());
  EXPECT_EQ(*d.depth_range, glm::vec2(1, 10));
}

TEST(Camera, RayThroughAPixelProjectsBackToIt) {
  Camera c;
  c.width = 64, c.height = 48, c.fx = 70, c.fy = 72, c.cx = 31.5f, c.cy = 25;
  c.R = glm::mat3(glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0));  // a rotation (columns)
  c.t = glm::vec3(0.5f, -1, 3);
  const glm::vec3 o = c.center();
  EXPECT_NEAR(glm::length(c.to_camera(o)), 0, 1e-5);
  for (glm::vec2 px : {glm::vec2(0.5f, 0.5f), glm::vec2(40.25f, 7.75f), glm::vec2(63.5f, 47.5f)}) {
    const glm::vec3 p = o + 3.0f * c.ray_direction(px.x, px.y);
    expect_near(project(c, p), px, 1e-3f);
  }
  const Camera half = c.resized(32, 24);
  EXPECT_FLOAT_EQ(half.fx, 35);
  EXPECT_FLOAT_EQ(half.cx, 15.75f);
  // The same world point lands at half the (continuous) pixel coordinates.
  const glm::vec3 p = o + 2.0f * c.ray_direction(10, 20);
  expect_near(project(half, p), {5, 10}, 1e-3f);
}

TEST(Camera, LegoLooksAtTheOrigin) {
  GORIS_REQUIRE_SHARED("datasets/lego");
  const Dataset d = load_dataset(test::shared_dir() / "datasets/lego");
  for (const View* v : {&d.train.front(), &d.train.back(), &d.test.front()}) {
    const Camera& c = v->camera;
    EXPECT_GT(c.to_camera({0, 0, 0}).z, 2.0f) << v->name;
    const glm::vec2 uv = project(c, {0, 0, 0});
    EXPECT_NEAR(uv.x, 200, 20) << v->name;
    EXPECT_NEAR(uv.y, 200, 20) << v->name;
    // Blender's world up (+z) points up in the image for these upper-hemisphere cameras.
    EXPECT_LT(project(c, {0, 0, 0.5f}).y, uv.y) << v->name;
  }
}

}  // namespace
}  // namespace goris
