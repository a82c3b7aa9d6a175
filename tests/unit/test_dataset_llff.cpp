// LLFF poses_bounds.npy: focal scaled to the image files, hold-out split, masks folder, bad input.
#include <gtest/gtest.h>

#include "core/io/dataset.h"
#include "core/io/loaders/llff_poses.h"
#include "tests/support/test_support.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
namespace fs = std::filesystem;
using test::expect_error;

// n views, identity-like poses moving along x, hwf for 600x800 originals with f = 1000; files are 40x30.
std::vector<double> poses(int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) {
    const std::vector<double> row = {0, 1, 0, double(i), 600,  //
                                     1, 0, 0, 0, 800,          //
                                     0, 0, -1, -5, 1000, 0.5 + i, 20.0 - i};
    v.insert(v.end(), row.begin(), row.end());
  }
  return v;
}

fs::path make_scene(const std::string& name, int n) {
  const auto dir = test::scratch_dir(name);
  test::write_bytes(dir / "poses_bounds.npy", test::npy_bytes({size_t(n), 17}, poses(n)));
  for (int i = 0; i < n; ++i) test::write_png(dir / "images" / ("IMG_" + std::to_string(100 + i) + ".png"), 40, 30);
  return dir;
}

TEST(DatasetLlff, FocalScaledSplitAndMasks) {
  const auto dir = make_scene("llff_basic", 10);
  test::write_png(dir / "masks/IMG_101.png", 40, 30, 1);
  EXPECT_EQ(detect_dataset_format(dir), "llff");
  const Dataset d = load_dataset(dir);
  EXPECT_EQ(d.format, "llff");
  ASSERT_EQ(d.test.size(), 2u);  // 0 and 8
  ASSERT_EQ(d.train.size(), 8u);
  EXPECT_EQ(d.test[1].name, "IMG_108");
  const Camera& c = d.train[0].camera;
  EXPECT_EQ(d.train[0].name, "IMG_101");
  EXPECT_FLOAT_EQ(c.fx, 50);  // 1000 * 40 / 800
  EXPECT_FLOAT_EQ(c.fy, 50);
  EXPECT_FLOAT_EQ(c.cx, 20);
  EXPECT_NEAR(glm::length(c.center() - glm::vec3(1, 0, -5)), 0, 1e-6);
  EXPECT_EQ(d.train[0].object_mask->filename(), "IMG_101.png");
  EXPECT_FALSE(d.train[1].object_mask.has_value());
  ASSERT_TRUE(d.depth_range.has_value());
  EXPECT_FLOAT_EQ(d.depth_range->x, 0.5f);
  EXPECT_FLOAT_EQ(d.depth_range->y, 20.0f);
  DatasetOptions o;
  o.test_every = 4;
  EXPECT_EQ(load_dataset(dir / "poses_bounds.npy", o).test.size(), 3u);  // 0, 4, 8
  o.downscale = 4;
  const Dataset q = load_dataset(dir, o);
  EXPECT_EQ(q.train[0].camera.width, 10);
  EXPECT_FLOAT_EQ(q.train[0].camera.fx, 12.5f);
  EXPECT_EQ(load_view_object_mask(q.train[0]).width, 10);
}

TEST(DatasetLlff, BadInput) {
  const auto dir = make_scene("llff_bad", 3);
  // One image too many.
  test::write_png(dir / "images/IMG_999.png", 40, 30);
  expect_error([&] { load_dataset(dir); }, {"poses_bounds.npy", "has 3 poses", "has 4 images"});
  fs::remove(dir / "images/IMG_999.png");
  // Wrong shape, truncated data.
  test::write_bytes(dir / "poses_bounds.npy", test::npy_bytes({3, 15}, std::vector<double>(45, 1.0)));
  expect_error([&] { load_dataset(dir); }, {"poses_bounds.npy", "N x 17", "(3, 15)"});
  auto bytes = test::npy_bytes({3, 17}, poses(3));
  bytes.resize(bytes.size() - 8);
  test::write_bytes(dir / "poses_bounds.npy", bytes);
  expect_error([&] { load_dataset(dir); }, {"poses_bounds.npy", "truncated .npy data"});
  test::write_bytes(dir / "poses_bounds.npy", test::npy_bytes({0, 17}, {}));
  expect_error([&] { load_dataset(dir); }, {"poses_bounds.npy", "no poses"});
  auto p = poses(3);
  p[17 + 14] = 0;  // focal of row 1
  test::write_bytes(dir / "poses_bounds.npy", test::npy_bytes({3, 17}, p));
  expect_error([&] { load_dataset(dir); }, {"poses_bounds.npy", "row 1", "must be positive"});
  // Images with another aspect ratio than hwf.
  test::write_bytes(dir / "poses_bounds.npy", test::npy_bytes({3, 17}, poses(3)));
  test::write_png(dir / "images/IMG_102.png", 40, 40);
  expect_error([&] { load_dataset(dir); }, {"IMG_102.png", "40x40", "row 2", "800x600", "aspect"});
  // A mask of the wrong size.
  test::write_png(dir / "images/IMG_102.png", 40, 30);
  test::write_png(dir / "masks/IMG_100.png", 20, 15, 1);
  expect_error([&] { load_dataset(dir); }, {"masks/IMG_100.png", "20x15", "IMG_100.png", "40x30"});
  // No images folder, an empty one.
  fs::remove_all(dir / "masks");
  fs::remove_all(dir / "images");
  expect_error([&] { load_dataset(dir); }, {"llff_bad/images", "images folder not found"});
  fs::create_directories(dir / "images");
  expect_error([&] { load_dataset(dir); }, {"llff_bad/images", "no images"});
}

TEST(DatasetLlff, Goldcape) {
  GORIS_REQUIRE_SHARED("datasets/goldcape");
  const fs::path root = test::shared_dir() / "datasets/goldcape";
  const Dataset d = load_dataset(root);
  EXPECT_EQ(d.format, "llff");
  EXPECT_EQ(d.view_count(), 119u);
  EXPECT_EQ(d.test.size(), 15u);
  const NpyArray a = load_npy(root / "poses_bounds.npy");
  const double f_orig = a.at(0, 14);
  for (const auto* split : {&d.train, &d.test})
    for (const View& v : *split) {
      EXPECT_EQ(v.camera.width, 456);
      EXPECT_EQ(v.camera.height, 456);
      EXPECT_TRUE(v.object_mask.has_value()) << v.name;
      EXPECT_FALSE(v.camera.has_distortion());
    }
  EXPECT_NEAR(d.test[0].camera.fx, f_orig * 456.0 / 3648.0, 1e-3);  // intrinsics scaled to 456
  EXPECT_FLOAT_EQ(d.test[0].camera.cx, 228);
  EXPECT_EQ(d.test[0].image.filename(), "IMG_5881.JPG");
  EXPECT_EQ(d.test[0].object_mask->filename(), "IMG_5881.png");
  const Image m = load_view_object_mask(d.train[0]);
  EXPECT_EQ(m.width, 456);
  EXPECT_EQ(m.channels, 1);
}

}  // namespace
}  // namespace goris
