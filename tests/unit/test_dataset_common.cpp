// Format detection, options, scene bounds: what all loaders share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/io/dataset.h"
#include "tests/support/test_support.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
namespace fs = std::filesystem;
using test::expect_error;

TEST(DatasetCommon, UnrecognisedPaths) {
  const auto dir = test::scratch_dir("common_detect");
  expect_error([&] { load_dataset(dir / "absent"); }, {"common_detect/absent", "not found"});
  expect_error([&] { load_dataset(dir); }, {"common_detect", "no data set recognised", "transforms_train.json", "sparse/0"});
  test::write_text(dir / "notes.txt", "hello");
  expect_error([&] { load_dataset(dir / "notes.txt"); }, {"notes.txt", "not a data set file"});
  expect_error([&] { detect_dataset_format(dir / "absent"); }, {"absent", "not found"});
}

TEST(DatasetCommon, InvalidOptions) {
  const auto dir = test::scratch_dir("common_options");
  DatasetOptions o;
  o.downscale = 0;
  expect_error([&] { load_dataset(dir, o); }, {"downscale"});
  o = {};
  o.target_width = -1;
  expect_error([&] { load_dataset(dir, o); }, {"target width"});
  o = {};
  o.test_every = -2;
  expect_error([&] { load_dataset(dir, o); }, {"test hold-out"});
}

TEST(DatasetCommon, ScaledSize) {
  DatasetOptions o;
  EXPECT_EQ(scaled_size(400, 300, o), (ImageSize{400, 300}));
  o.downscale = 2;
  EXPECT_EQ(scaled_size(400, 300, o), (ImageSize{200, 150}));
  o.downscale = 3;
  EXPECT_EQ(scaled_size(400, 301, o), (ImageSize{133, 100}));
  o.downscale = 1000;
  EXPECT_EQ(scaled_size(400, 300, o), (ImageSize{1, 1}));
  o.target_width = 100;  // wins over downscale
  EXPECT_EQ(scaled_size(400, 300, o), (ImageSize{100, 75}));
}

TEST(DatasetCommon, CameraBoundsEncloseTheCentres) {
  std::vector<View> views(3);
  const glm::vec3 centres[3] = {{1, 0, 0}, {-1, 0, 0}, {0, 3, 0}};
  for (int i = 0; i < 3; ++i) views[i].camera.t = -centres[i];  // R = identity
  const SceneBounds b = camera_bounds(views);
  EXPECT_NEAR(glm::length(b.center - glm::vec3(0, 1, 0)), 0, 1e-6);
  EXPECT_NEAR(b.radius, 1.1f * 2.0f, 1e-5);
  EXPECT_EQ(camera_bounds({}).radius, 0.0f);
}

TEST(DatasetCommon, ViewImagesLandOnTheRequestedDevice) {
  const auto dir = test::scratch_dir("common_device");
  nlohmann::json j;
  j["camera_angle_x"] = 0.7;
  j["frames"] = {{{"file_path", "a"}, {"transform_matrix", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 3}, {0, 0, 0, 1}}}}};
  test::write_text(dir / "transforms_train.json", j.dump());
  test::write_png(dir / "a.png", 6, 4, 3, 0.4f);
  const Dataset d = load_dataset(dir);
  const Image im = load_view_image(d.train[0], {}, Device::CPU);
  EXPECT_EQ(im.pixels.device(), Device::CPU);
  EXPECT_NEAR(im.pixels[0], 0.4f, 1.0 / 255);
  if (cuda_device_count() > 0) {
    const Image g = load_view_image(d.train[0], {}, Device::CUDA);
    EXPECT_EQ(g.pixels.device(), Device::CUDA);
    EXPECT_EQ(g.pixels.to_host(), im.pixels.to_host());
  }
}

}  // namespace
}  // namespace goris

TEST(DatasetCommon, UndistortImageMovesPixelsWhereThePinholeCameraSeesThem) {
  // A bright dot where the lens puts the ray of pinhole pixel (110, 100); undistorted, it lands there.
  goris::Camera pin;
  pin.width = pin.height = 128;
  pin.fx = pin.fy = 100;
  pin.cx = pin.cy = 64;
  goris::Distortion lens;
  lens.k1 = 0.5f, lens.p1 = 0.01f;
  const double x = (110.5 - 64) / 100, y = (100.5 - 64) / 100, r2 = x * x + y * y;
  const double radial = 1 + lens.k1 * r2;
  const double xd = x * radial + 2 * lens.p1 * x * y, yd = y * radial + lens.p1 * (r2 + 2 * y * y);
  const int u = int(std::floor(xd * 100 + 64)), v = int(std::floor(yd * 100 + 64));
  goris::Image distorted(128, 128, 1);
  for (std::size_t p = 0; p < distorted.pixel_count(); ++p) distorted.pixels[p] = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) distorted.pixels[std::size_t(v + dy) * 128 + std::size_t(u + dx)] = 1.0f;
  ASSERT_GT(std::hypot(u - 110, v - 100), 3.0) << "the lens moves the dot";
  const goris::Image out = goris::undistort_image(distorted, pin, lens);
  const std::vector<float> px = out.pixels.to_host();
  const auto peak = std::max_element(px.begin(), px.end()) - px.begin();
  EXPECT_NEAR(double(peak % 128), 110.0, 1.0);
  EXPECT_NEAR(double(peak / 128), 100.0, 1.0);
  EXPECT_EQ(out.width, 128);
  EXPECT_EQ(out.channels, 1);
}
