// Gaussians that only the target's pixels showed: on the table-and-box scene, a cluster below the table
// under the box (every view sees it only through the box) is unsupported; the table, which the views see
// around the box, is not; a cluster beside the box, seen past it, is not either.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/removal/gaussian_pixel_weights.h"
#include "render/removal/select_view.h"
#include "render/removal/unsupported_gaussians.h"
#include "tests/support/table_box_scene.h"

namespace goris {
namespace {

struct Scene {
  test::SceneBuilder s;
  std::size_t below_first = 0, below_end = 0, beside_first = 0, beside_end = 0;
};

// The table without the box's footprint (a real capture never sees it), the box resting on it, a cluster
// just below the footprint and one beside the box.
Scene junk_scene() {
  Scene sc;
  for (int i = 0; i <= 96; ++i)
    for (int j = 0; j <= 96; ++j) {
      const float x = -2.4f + 0.05f * i, y = -2.4f + 0.05f * j;
      if (std::fabs(x) < test::kHalf && std::fabs(y) < test::kHalf) continue;
      sc.s.add({x, y, 0.0f}, {0.035f, 0.035f, 0.004f}, 0.6f, false);
    }
  for (float x = -test::kHalf + 0.025f; x < test::kHalf; x += 0.05f)
    for (float y = -test::kHalf + 0.025f; y < test::kHalf; y += 0.05f)
      for (float z = 0.025f; z < 1.0f; z += 0.05f) sc.s.add({x, y, z}, glm::vec3(0.03f), 0.2f, true);
  sc.below_first = sc.s.target.size();
  for (float x = -0.075f; x < 0.1f; x += 0.05f)
    for (float y = -0.075f; y < 0.1f; y += 0.05f) sc.s.add({x, y, -0.04f}, glm::vec3(0.02f), 0.9f, false);
  sc.below_end = sc.beside_first = sc.s.target.size();
  for (float z = 0.1f; z < 0.5f; z += 0.05f) sc.s.add({0.5f, 0.5f, z}, glm::vec3(0.03f), 0.9f, false);
  sc.beside_end = sc.s.target.size();
  return sc;
}

TEST(UnsupportedGaussians, WhatOnlyTheTargetShowedGoesTheRestStays) {
  const Scene sc = junk_scene();
  const GaussianModel model = sc.s.model();
  const std::vector<Camera> cams = test::table_cameras();
  const UnsupportedWeights w = unsupported_weights(model, sc.s.target, cams, RasterSettings{});
  const std::vector<std::uint8_t> drop = unsupported_gaussians(w, sc.s.target);
  ASSERT_EQ(drop.size(), model.count());

  std::size_t below = 0, below_seen = 0;
  for (std::size_t i = sc.below_first; i < sc.below_end; ++i) {
    below += drop[i];
    below_seen += w.inside[i] >= 0.5f;
    EXPECT_LT(w.outside[i], 0.01f * (w.inside[i] + w.outside[i])) << "below-table Gaussian " << i;
  }
  EXPECT_GT(below_seen, 0u);
  EXPECT_EQ(below, below_seen);  // every one the removed scene shows where the box was
  for (std::size_t i = sc.beside_first; i < sc.beside_end; ++i) EXPECT_FALSE(drop[i]) << "beside the box " << i;
  std::size_t table = 0, box = 0;
  for (std::size_t i = 0; i < sc.below_first; ++i) {
    if (sc.s.target[i]) {
      box += drop[i];
      EXPECT_EQ(w.inside[i] + w.outside[i], 0.0f);  // the selection itself is not rendered
    } else {
      table += drop[i];
    }
  }
  EXPECT_EQ(box, 0u);
  EXPECT_EQ(table, 0u);
  // The table around the box carries weight outside the box's pixels.
  EXPECT_GT(w.outside[0] + w.outside[sc.below_first / 2], 0.0f);
}

TEST(GaussianPixelWeights, ALoneGaussiansWeightsSumToItsAlphaImage) {
  test::SceneBuilder s;
  s.add({0.05f, -0.03f, 0.3f}, {0.2f, 0.1f, 0.05f}, 0.5f, false);
  const GaussianModel model = s.model();
  const Camera cam = test::table_cameras()[0];
  Mask half(cam.width, cam.height);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width / 2; ++x) half.data[std::size_t(y) * cam.width + x] = 255;
  const PixelWeights w = gaussian_pixel_weights(model, {cam}, {half}, RasterSettings{});
  const std::vector<float> alpha = rasterize(plain_gaussian_view(model), cam, {}, Device::CPU).gbuffer.alpha.to_host();
  double in = 0, out = 0;
  for (std::size_t p = 0; p < alpha.size(); ++p) (half.data[p] ? in : out) += alpha[p];
  EXPECT_GT(in, 10.0);
  EXPECT_GT(out, 10.0);
  EXPECT_NEAR(w.inside[0], in, 1e-3 * in);
  EXPECT_NEAR(w.outside[0], out, 1e-3 * out);
  EXPECT_THROW(gaussian_pixel_weights(model, {cam}, {}, RasterSettings{}), Error);
  EXPECT_THROW(gaussian_pixel_weights(model, {cam}, {Mask(3, 3)}, RasterSettings{}), Error);
}

TEST(UnsupportedGaussians, NothingSelectedOrAWrongSizedSelection) {
  const Scene sc = junk_scene();
  const GaussianModel model = sc.s.model();
  const std::vector<Camera> cams = {test::table_cameras()[0]};
  // Nothing selected: no pixel is the target's, so nothing is unsupported.
  const std::vector<std::uint8_t> none(model.count(), 0);
  const std::vector<std::uint8_t> drop = unsupported_gaussians(unsupported_weights(model, none, cams, {}), none);
  for (auto d : drop) EXPECT_EQ(d, 0);
  EXPECT_THROW(unsupported_weights(model, std::vector<std::uint8_t>(3, 1), cams, {}), Error);
}

}  // namespace
}  // namespace goris
