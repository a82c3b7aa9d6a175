// NeRF-synthetic / GOR-IS folders: transforms_{train,test}.json, masks by name, downscale, bad input.
#include <gtest/gtest.h>

#include <cmath>

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

// A GOR-IS-style scene: 2 train views with object and glossy masks, 1 test view with mask and full_ image.
fs::path make_scene(const std::string& name, int w = 16, int h = 12) {
  const auto dir = test::scratch_dir(name);
  json train, test;
  train["camera_angle_x"] = test["camera_angle_x"] = 0.8;
  train["frames"] = {frame("./train/r_000", 0), frame("./train/r_001", 1)};
  test["frames"] = {frame("./test/r_000", 0.5)};
  test::write_text(dir / "transforms_train.json", train.dump(1));
  test::write_text(dir / "transforms_test.json", test.dump(1));
  for (const char* f : {"train/r_000", "train/r_001", "test/r_000", "test/full_000"}) test::write_png(dir / (std::string(f) + ".png"), w, h, 4);
  for (const char* f : {"train/mask_000", "train/mask_001", "train/gloss_000", "train/gloss_001", "test/mask_000"})
    test::write_png(dir / (std::string(f) + ".png"), w, h, 1, 1.0f);
  return dir;
}

TEST(DatasetNerf, LoadsSplitsAndMatchesMasksByName) {
  const auto dir = make_scene("nerf_layout");
  EXPECT_EQ(detect_dataset_format(dir), "nerf-synthetic");
  const Dataset d = load_dataset(dir);
  EXPECT_EQ(d.format, "nerf-synthetic");
  ASSERT_EQ(d.train.size(), 2u);
  ASSERT_EQ(d.test.size(), 1u);
  EXPECT_EQ(d.train[1].name, "r_001");
  EXPECT_EQ(d.train[1].image.filename(), "r_001.png");
  EXPECT_EQ(d.train[1].object_mask->filename(), "mask_001.png");
  EXPECT_EQ(d.train[1].glossy_mask->filename(), "gloss_001.png");
  EXPECT_FALSE(d.train[1].full_image.has_value());
  EXPECT_EQ(d.test[0].object_mask->filename(), "mask_000.png");
  EXPECT_FALSE(d.test[0].glossy_mask.has_value());
  EXPECT_EQ(d.test[0].full_image->filename(), "full_000.png");
  EXPECT_EQ(d.train[0].camera.width, 16);
  EXPECT_EQ(d.train[0].camera.height, 12);
  EXPECT_NEAR(d.train[0].camera.fx, 8.0 / std::tan(0.4), 1e-4);
  EXPECT_TRUE(d.points.xyz.empty());
  EXPECT_TRUE(d.warnings.empty());
  // Opening the json file directly is the same data set.
  EXPECT_EQ(load_dataset(dir / "transforms_test.json").view_count(), 3u);
}

TEST(DatasetNerf, DownscaleAppliesToImagesMasksAndIntrinsics) {
  const auto dir = make_scene("nerf_downscale", 16, 12);
  const Dataset full = load_dataset(dir);
  DatasetOptions o;
  o.downscale = 2;
  const Dataset d = load_dataset(dir, o);
  const View& v = d.train[0];
  EXPECT_EQ(v.camera.width, 8);
  EXPECT_EQ(v.camera.height, 6);
  EXPECT_EQ(v.source_width, 16);
  EXPECT_FLOAT_EQ(v.camera.fx, full.train[0].camera.fx / 2);
  EXPECT_FLOAT_EQ(v.camera.cx, 4);
  const Image im = load_view_image(v, o);
  EXPECT_EQ(im.width, 8);
  EXPECT_EQ(im.height, 6);
  EXPECT_EQ(im.channels, 3);
  const Image mask = load_view_object_mask(v);
  EXPECT_EQ(mask.width, 8);
  EXPECT_EQ(mask.channels, 1);
  EXPECT_NEAR(mask.pixels[0], 1.0f, 1e-6);
  EXPECT_EQ(load_view_glossy_mask(v).height, 6);
  EXPECT_EQ(load_view_full_image(d.test[0], o).width, 8);
  expect_error([&] { load_view_glossy_mask(d.test[0]); }, {"r_000.png", "no glossy-surface mask"});

  DatasetOptions r;
  r.target_width = 4;  // --resolution 4
  const Dataset dr = load_dataset(dir, r);
  EXPECT_EQ(dr.test[0].camera.width, 4);
  EXPECT_EQ(dr.test[0].camera.height, 3);
  EXPECT_EQ(load_view_object_mask(dr.test[0]).height, 3);
}

TEST(DatasetNerf, BackgroundColourIsUsedForTransparentPixels) {
  const auto dir = make_scene("nerf_background");
  Image rgba(16, 12, 4);
  rgba.pixels.fill_zero();  // fully transparent
  save_png(dir / "train/r_000.png", rgba);
  DatasetOptions o;
  const Dataset d = load_dataset(dir, o);
  EXPECT_EQ(load_view_image(d.train[0], o).pixels[0], 0.0f);
  o.background = glm::vec3(1, 0.5f, 0);
  const Image white = load_view_image(d.train[0], o);
  EXPECT_EQ(white.pixels[0], 1.0f);
  EXPECT_EQ(white.pixels[1], 0.5f);
}

TEST(DatasetNerf, MissingFilesAndFolders) {
  const auto dir = make_scene("nerf_missing");
  fs::remove(dir / "train/r_001.png");
  expect_error([&] { load_dataset(dir); }, {"transforms_train.json", "frame 1", "r_001", "image not found"});
  fs::remove(dir / "transforms_train.json");
  expect_error([&] { load_dataset(dir); }, {"nerf_missing", "no data set recognised"});
  expect_error([&] { load_dataset(dir / "nope"); }, {"nope", "not found"});
}

TEST(DatasetNerf, MalformedJsonReportsTheBytePosition) {
  const auto dir = make_scene("nerf_json");
  test::write_text(dir / "transforms_train.json", "{\"camera_angle_x\": 0.5, \"frames\": [ {\"file_path\": }");
  const std::string msg = expect_error([&] { load_dataset(dir); }, {"transforms_train.json", "malformed JSON at byte"});
  EXPECT_NE(msg.find("byte 51"), std::string::npos) << msg;
  // A number beyond double's range (found by fuzz_json).
  test::write_text(dir / "transforms_train.json", "{\"camera_angle_x\": 1e999, \"frames\": []}");
  expect_error([&] { load_dataset(dir); }, {"transforms_train.json", "malformed JSON", "number overflow"});
}

TEST(DatasetNerf, WrongKeysAndTypes) {
  const auto dir = make_scene("nerf_keys");
  const fs::path f = dir / "transforms_train.json";
  auto with = [&](json j) {
    test::write_text(f, j.dump());
    return [&] { load_dataset(dir); };
  };
  json good = {{"camera_angle_x", 0.8}, {"frames", {frame("./train/r_000", 0)}}};
  json j = good;
  j.erase("frames");
  expect_error(with(j), {"transforms_train.json", "no 'frames'"});
  j = good;
  j["frames"] = "x";
  expect_error(with(j), {"transforms_train.json", "'frames' must be an array"});
  j = good;
  j.erase("camera_angle_x");
  expect_error(with(j), {"transforms_train.json", "no focal length"});
  j = good;
  j["camera_angle_x"] = "wide";
  expect_error(with(j), {"transforms_train.json", "'camera_angle_x' must be a number"});
  j = good;
  j["frames"][0]["transform_matrix"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  expect_error(with(j), {"transforms_train.json", "frame 0", "4x4"});
  j = good;
  j["frames"][0]["transform_matrix"][3] = {0, 0, 1, 1};
  expect_error(with(j), {"transforms_train.json", "last row"});
  j = good;
  j["frames"][0]["transform_matrix"] = {{2, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  expect_error(with(j), {"transforms_train.json", "frame 0", "not orthonormal"});
  j = good;
  j["frames"][0]["transform_matrix"] = {{-1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  expect_error(with(j), {"transforms_train.json", "reflection"});
  j = good;
  j["frames"][0]["transform_matrix"][1][3] = 1e60;  // beyond float (found by fuzz_json)
  expect_error(with(j), {"transforms_train.json", "frame 0", "camera position out of range"});
  for (const double angle : {1e-300, 1e-30, 3.14159, 3.1}) {  // absurd fields of view: fx of 1e32 or ~0
    j = good;
    j["camera_angle_x"] = angle;
    expect_error(with(j), {"transforms_train.json", "'camera_angle_x'", "field of view must lie between"});
  }
  j = good;
  j["frames"][0].erase("file_path");
  expect_error(with(j), {"transforms_train.json", "frame 0", "no 'file_path'"});
  j = good;
  j["frames"][0]["file_path"] = 3;
  expect_error(with(j), {"transforms_train.json", "'file_path' must be a non-empty string"});
  j = good;
  j = json::array();
  expect_error(with(j), {"transforms_train.json", "top level"});
}

TEST(DatasetNerf, ZeroImagesIsAnError) {
  const auto dir = make_scene("nerf_zero");
  test::write_text(dir / "transforms_train.json", R"({"camera_angle_x": 0.8, "frames": []})");
  test::write_text(dir / "transforms_test.json", R"({"camera_angle_x": 0.8, "frames": []})");
  expect_error([&] { load_dataset(dir); }, {"transforms_train.json", "no images"});
}

TEST(DatasetNerf, MaskSizeMustMatchItsImage) {
  const auto dir = make_scene("nerf_mask_size");
  test::write_png(dir / "train/gloss_001.png", 8, 12, 1);
  expect_error([&] { load_dataset(dir); }, {"gloss_001.png", "is 8x12", "r_001.png", "16x12"});
}

TEST(DatasetNerf, ImageChangedAfterLoading) {
  const auto dir = make_scene("nerf_changed");
  const Dataset d = load_dataset(dir);
  test::write_png(dir / "train/r_000.png", 10, 10, 4);
  expect_error([&] { load_view_image(d.train[0], {}); }, {"r_000.png", "is 10x10, expected 16x12"});
}

TEST(DatasetNerf, SteelSnowman) {
  GORIS_REQUIRE_SHARED("datasets/steel_snowman");
  const Dataset d = load_dataset(test::shared_dir() / "datasets/steel_snowman");
  ASSERT_EQ(d.train.size(), 100u);
  ASSERT_EQ(d.test.size(), 60u);
  for (const auto* split : {&d.train, &d.test})
    for (const View& v : *split) {
      EXPECT_EQ(v.camera.width, 256);
      EXPECT_EQ(v.camera.height, 256);
      EXPECT_TRUE(v.object_mask.has_value()) << v.name;
    }
  for (const View& v : d.train) EXPECT_TRUE(v.glossy_mask.has_value()) << v.name;
  for (const View& v : d.test) EXPECT_TRUE(v.full_image.has_value()) << v.name;
  // One view's pixels: composited on black, masks in [0, 1] with both values present.
  const Image im = load_view_image(d.train[0], {});
  EXPECT_EQ(im.channels, 3);
  const Image m = load_view_glossy_mask(d.train[0]);
  float lo = 1, hi = 0;
  for (size_t i = 0; i < m.pixels.size(); ++i) lo = std::min(lo, m.pixels[i]), hi = std::max(hi, m.pixels[i]);
  EXPECT_EQ(lo, 0.0f);
  EXPECT_EQ(hi, 1.0f);
}

TEST(DatasetNerf, Lego) {
  GORIS_REQUIRE_SHARED("datasets/lego");
  DatasetOptions o;
  o.downscale = 2;
  const Dataset d = load_dataset(test::shared_dir() / "datasets/lego", o);
  EXPECT_EQ(d.train.size(), 100u);
  EXPECT_EQ(d.test.size(), 50u);
  EXPECT_EQ(d.train[0].source_width, 400);
  EXPECT_EQ(d.train[0].camera.width, 200);
  EXPECT_FALSE(d.train[0].object_mask.has_value());
  const Image im = load_view_image(d.train[0], o);
  EXPECT_EQ(im.width, 200);
  EXPECT_EQ(im.height, 200);
}

// Data sets that load but cannot train well say so, naming the camera file.
TEST(DatasetNerf, WarnsOfOneViewOneCameraPositionAndDuplicateFrames) {
  const auto dir = make_scene("nerf_degenerate");
  auto warnings_with = [&](std::initializer_list<json> frames) {
    json j;
    j["camera_angle_x"] = 0.8;
    j["frames"] = json::array();
    for (const json& f : frames) j["frames"].push_back(f);
    test::write_text(dir / "transforms_train.json", j.dump());
    std::string all;
    for (const std::string& w : load_dataset(dir).warnings) all += w + "\n";
    return all;
  };
  std::string w = warnings_with({frame("./train/r_000", 0)});
  EXPECT_NE(w.find("transforms_train.json: only one training view"), std::string::npos) << w;
  w = warnings_with({frame("./train/r_000", 0), frame("./train/r_001", 0)});
  EXPECT_NE(w.find("all 2 training cameras are at the same position"), std::string::npos) << w;
  w = warnings_with({frame("./train/r_000", 0), frame("./train/r_000", 1)});
  EXPECT_NE(w.find("r_000.png is listed 2 times"), std::string::npos) << w;
  EXPECT_EQ(warnings_with({frame("./train/r_000", 0), frame("./train/r_001", 1)}), "");
}

}  // namespace
}  // namespace goris
