// instant-ngp transforms.json: pixel intrinsics, distortion, skipped frames, hold-out split, bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/io/dataset.h"
#include "tests/support/test_support.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using test::expect_error;

json frame(const std::string& path, double x) {
  return {{"file_path", path}, {"transform_matrix", {{1, 0, 0, x}, {0, 0, -1, -4}, {0, 1, 0, 0}, {0, 0, 0, 1}}}};
}

// `n` frames images/0000.png.. of 20x10 pixels; intrinsics declared for w x h.
fs::path make_capture(const std::string& name, int n, int w = 20, int h = 10) {
  const auto dir = test::scratch_dir(name);
  json j = {{"fl_x", 30.0}, {"fl_y", 31.0}, {"cx", 9.5}, {"cy", 5.5}, {"w", w}, {"h", h},
            {"k1", 0.05}, {"k2", -0.08}, {"p1", -0.001}, {"p2", 0.0002}, {"aabb_scale", 4}};
  for (int i = 0; i < n; ++i) {
    char name_buf[32];
    std::snprintf(name_buf, sizeof name_buf, "images/%04d.png", i);
    j["frames"].push_back(frame(name_buf, i));
    test::write_png(dir / name_buf, 20, 10);
  }
  test::write_text(dir / "transforms.json", j.dump(1));
  return dir;
}

TEST(DatasetNgp, IntrinsicsDistortionAndEveryEighthHeldOut) {
  const auto dir = make_capture("ngp_basic", 10);
  EXPECT_EQ(detect_dataset_format(dir), "instant-ngp");
  const Dataset d = load_dataset(dir);
  EXPECT_EQ(d.format, "instant-ngp");
  ASSERT_EQ(d.test.size(), 2u);  // frames 0 and 8
  ASSERT_EQ(d.train.size(), 8u);
  EXPECT_EQ(d.test[0].name, "0000");
  EXPECT_EQ(d.test[1].name, "0008");
  EXPECT_EQ(d.train[0].name, "0001");
  const Camera& c = d.train[0].camera;
  EXPECT_FLOAT_EQ(c.fx, 30);
  EXPECT_FLOAT_EQ(c.fy, 31);
  EXPECT_FLOAT_EQ(c.cx, 9.5f);
  EXPECT_FLOAT_EQ(c.dist.k2, -0.08f);
  EXPECT_FLOAT_EQ(c.dist.p1, -0.001f);
  EXPECT_TRUE(c.has_distortion());

  DatasetOptions all;
  all.test_every = 0;
  EXPECT_EQ(load_dataset(dir, all).train.size(), 10u);
  DatasetOptions third;
  third.test_every = 3;
  EXPECT_EQ(load_dataset(dir, third).test.size(), 4u);  // 0, 3, 6, 9
}

TEST(DatasetNgp, MissingImagesAreSkippedWithOneWarning) {
  const auto dir = make_capture("ngp_missing", 6);
  fs::remove(dir / "images/0002.png");
  fs::remove(dir / "images/0004.png");
  const Dataset d = load_dataset(dir / "transforms.json");
  EXPECT_EQ(d.view_count(), 4u);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("skipped 2 of 6 frames"), std::string::npos) << d.warnings[0];
  EXPECT_NE(d.warnings[0].find("images/0002.png"), std::string::npos) << d.warnings[0];
  EXPECT_NE(d.warnings[0].find("transforms.json"), std::string::npos) << d.warnings[0];
  fs::remove_all(dir / "images");
  expect_error([&] { load_dataset(dir); }, {"transforms.json", "no images", "all 6 frames", "images/0000.png"});
  test::write_text(dir / "transforms.json", R"({"fl_x": 10, "frames": []})");
  expect_error([&] { load_dataset(dir); }, {"transforms.json", "no images"});
}

TEST(DatasetNgp, DeclaredSizeIsFittedToTheFiles) {
  // Intrinsics for 40x20, files are 20x10: a half-size copy, so the intrinsics halve.
  const auto dir = make_capture("ngp_fit", 2, 40, 20);
  const Dataset d = load_dataset(dir);
  const Camera& c = d.train[0].camera;
  EXPECT_EQ(c.width, 20);
  EXPECT_FLOAT_EQ(c.fx, 15);
  EXPECT_FLOAT_EQ(c.cy, 2.75f);
  // A different aspect ratio is an error naming both files.
  const auto bad = make_capture("ngp_aspect", 2, 40, 40);
  expect_error([&] { load_dataset(bad); }, {"0000.png", "20x10", "transforms.json", "40x40", "aspect"});
}

TEST(DatasetNgp, PerFrameIntrinsicsOverrideTheFile) {
  const auto dir = make_capture("ngp_per_frame", 2);
  json j = json::parse(test::read_text_file_for_test(dir / "transforms.json"));
  j["frames"][1]["fl_x"] = 50.0;
  test::write_text(dir / "transforms.json", j.dump());
  DatasetOptions o;
  o.test_every = 0;
  const Dataset d = load_dataset(dir, o);
  EXPECT_FLOAT_EQ(d.train[0].camera.fx, 30);
  EXPECT_FLOAT_EQ(d.train[1].camera.fx, 50);
}

TEST(DatasetNgp, MasksFolderByStem) {
  const auto dir = make_capture("ngp_masks", 3);
  test::write_png(dir / "masks/0001.png", 20, 10, 1);
  test::write_png(dir / "gloss/0002.jpg", 20, 10, 1);
  DatasetOptions o;
  o.test_every = 0;
  const Dataset d = load_dataset(dir, o);
  EXPECT_FALSE(d.train[0].object_mask.has_value());
  EXPECT_EQ(d.train[1].object_mask->filename(), "0001.png");
  EXPECT_EQ(d.train[2].glossy_mask->filename(), "0002.jpg");
  test::write_png(dir / "masks/0000.png", 10, 10, 1);
  expect_error([&] { load_dataset(dir, o); }, {"masks/0000.png", "10x10", "0000.png", "20x10"});
}

TEST(DatasetNgp, UnsupportedCamerasAndBadValues) {
  const auto dir = make_capture("ngp_bad", 1);
  json j = json::parse(test::read_text_file_for_test(dir / "transforms.json"));
  json k = j;
  k["is_fisheye"] = true;
  test::write_text(dir / "transforms.json", k.dump());
  expect_error([&] { load_dataset(dir); }, {"transforms.json", "fisheye"});
  k = j;
  k["camera_model"] = "OPENCV_FISHEYE";
  test::write_text(dir / "transforms.json", k.dump());
  expect_error([&] { load_dataset(dir); }, {"transforms.json", "OPENCV_FISHEYE", "not supported"});
  k = j;
  k["w"] = -3;
  test::write_text(dir / "transforms.json", k.dump());
  expect_error([&] { load_dataset(dir); }, {"transforms.json", "'w' must be a positive whole number"});
  k = j;
  k["fl_x"] = 0;
  test::write_text(dir / "transforms.json", k.dump());
  expect_error([&] { load_dataset(dir); }, {"transforms.json", "'fl_x' must be positive"});
}

TEST(DatasetNgp, Fox) {
  GORIS_REQUIRE_SHARED("datasets/fox");
  const Dataset d = load_dataset(test::shared_dir() / "datasets/fox");
  EXPECT_EQ(d.format, "instant-ngp");
  EXPECT_EQ(d.view_count(), 50u);
  EXPECT_TRUE(d.warnings.empty());
  for (const auto* split : {&d.train, &d.test})
    for (const View& v : *split) {
      EXPECT_EQ(v.camera.width, 540);
      EXPECT_EQ(v.camera.height, 960);
      EXPECT_TRUE(v.camera.has_distortion());
    }
  EXPECT_NEAR(d.train[0].camera.fx, 687.76, 1e-3);
  EXPECT_NEAR(d.train[0].camera.dist.k1, 0.0578421, 1e-7);
}

}  // namespace
}  // namespace goris
