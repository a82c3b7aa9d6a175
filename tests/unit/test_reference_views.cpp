// Reference-view choice (largest masks, seen from directions at least 20 degrees apart, relaxed by
// halving), the hole centroid, and the removed scene's maps rendered for inpainting.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/lift/reference_views.h"

namespace goris {
namespace {

constexpr float kPi = 3.14159265f;

// Camera centres on a horizontal circle of radius 3 around the origin, at the given azimuths (degrees).
std::vector<glm::vec3> ring(const std::vector<float>& azimuth_deg) {
  std::vector<glm::vec3> c;
  for (float a : azimuth_deg) c.emplace_back(3.0f * std::cos(a * kPi / 180.0f), 3.0f * std::sin(a * kPi / 180.0f), 1.0f);
  return c;
}

TEST(ReferenceViews, LargestMasksFromDifferentDirections) {
  // View 1 sees the hole from 5 degrees beside view 0: skipped for the next largest that is far enough.
  const auto choice = choose_reference_views({100, 95, 90, 80, 70, 60}, ring({0, 5, 60, 120, 180, 240}), glm::vec3(0.0f));
  EXPECT_EQ(choice.views, (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(choice.angle_threshold, (std::vector<float>{20, 20, 20}));
}

TEST(ReferenceViews, ThresholdIsHalvedWhenTooFewQualify) {
  // All within 9 degrees: 20 and 10 accept only view 0, 5 adds view 2 (6 degrees away), 2.5 adds
  // view 1 (3 degrees from both).
  const auto choice = choose_reference_views({100, 90, 80, 70}, ring({0, 3, 6, 9}), glm::vec3(0.0f));
  EXPECT_EQ(choice.views, (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(choice.angle_threshold, (std::vector<float>{20, 5, 2.5f}));
  // Identical directions: after the threshold drops below 1 degree the largest are taken anyway.
  const auto same = choose_reference_views({10, 30, 20, 5}, ring({0, 0, 0, 0}), glm::vec3(0.0f));
  EXPECT_EQ(same.views, (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(same.angle_threshold.back(), 0.0f);
}

TEST(ReferenceViews, FewOrNoCandidates) {
  EXPECT_EQ(choose_reference_views({0, 50, 0}, ring({0, 90, 180}), glm::vec3(0.0f)).views, (std::vector<int>{1}));
  ReferenceViewSettings s;
  s.min_pixels = 10;
  EXPECT_EQ(choose_reference_views({5, 50, 12}, ring({0, 90, 180}), glm::vec3(0.0f), s).views, (std::vector<int>{1, 2}));
  EXPECT_TRUE(choose_reference_views({0, 0}, ring({0, 90}), glm::vec3(0.0f)).views.empty());
  // Ties keep the lower index first.
  EXPECT_EQ(choose_reference_views({7, 7, 7}, ring({0, 120, 240}), glm::vec3(0.0f)).views, (std::vector<int>{0, 1, 2}));
  EXPECT_THROW(choose_reference_views({1, 2}, ring({0}), glm::vec3(0.0f)), Error);
}

TEST(ReferenceViews, DirectionsAreMeasuredTowardsTheHole) {
  // Cameras 0, 1, 2 stand 90 degrees apart around the origin, but the hole is far along the x axis: seen
  // from there, 1 and 2 are 5.7 degrees from 0 (and 11.4 from each other). So 20 and 10 accept only 0,
  // and 5 accepts 1 and then 2.
  const std::vector<glm::vec3> centers = {{3, 0, 0}, {0, 3, 0}, {0, -3, 0}};
  const auto choice = choose_reference_views({100, 90, 80}, centers, glm::vec3(30, 0, 0));
  EXPECT_EQ(choice.views, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(choice.angle_threshold, (std::vector<float>{20, 5, 5}));
  // Around the origin they are 90 degrees apart: all accepted at 20.
  EXPECT_EQ(choose_reference_views({100, 90, 80}, centers, glm::vec3(0.0f)).angle_threshold,
            (std::vector<float>{20, 20, 20}));
}

Camera top_camera(int size, float height) {
  Camera c;
  c.width = c.height = size;
  c.fx = c.fy = 40.0f;
  c.cx = c.cy = 0.5f * size;
  // Looking straight down -z from (0, 0, height): x right, y down in the image = -y world.
  c.R = glm::mat3(glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1));  // columns; symmetric here
  c.t = -(c.R * glm::vec3(0, 0, height));
  return c;
}

TEST(ReferenceViews, HoleCentroidIsTheMedianSurfacePoint) {
  const Camera cam = top_camera(16, 2.0f);
  InpaintMaskView m;
  m.mask = Mask(16, 16);
  m.removed_depth = Image(16, 16, 1);
  m.target_depth = Image(16, 16, 1);
  m.removed_depth.pixels.fill_zero();
  m.target_depth.pixels.fill_zero();
  for (int y = 6; y < 10; ++y)
    for (int x = 6; x < 10; ++x) {
      m.mask.set(x, y, true);
      m.removed_depth.pixels[std::size_t(y) * 16 + x] = 2.0f;  // the plane z = 0
    }
  m.mask.set(0, 0, true);  // one pixel without a removed surface: its target depth is used
  m.target_depth.pixels[0] = 1.0f;
  m.stats.masked = count_set(m.mask);
  std::vector<InpaintMaskView> masks;
  masks.push_back(std::move(m));
  const auto c = hole_centroid(masks, {cam});
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->z, 0.0f, 1e-5f);          // the median ignores the one point at z = 1
  // Columns 6..9 at z = 2 give x = (col + 0.5 - 8) * 2 / 40 = -0.075, -0.025, 0.025, 0.075 (four each);
  // the extra point (pixel (0, 0) at depth 1) sits at x = -0.1875, y = +0.1875 (image y is -world y):
  // the 9th of 17 values is -0.025 in x and +0.025 in y.
  EXPECT_NEAR(c->x, -0.025f, 1e-5f);
  EXPECT_NEAR(c->y, 0.025f, 1e-5f);
  const auto choice = choose_reference_views(masks, {cam});
  EXPECT_EQ(choice.views, (std::vector<int>{0}));

  masks[0].mask = Mask(16, 16);
  EXPECT_FALSE(hole_centroid(masks, {cam}).has_value());
  EXPECT_TRUE(choose_reference_views(masks, {cam}).views.empty());
}

TEST(ReferenceViews, RemovedMapsOfAFlatScene) {
  // One big flat opaque Gaussian on z = 0 under a camera 2 above it.
  GaussianModel m(Device::CPU);
  m.allocate(1);
  const float pos[3] = {0, 0, 0}, ls[3] = {std::log(3.0f), std::log(3.0f), std::log(0.01f)}, rot[4] = {1, 0, 0, 0},
              op = 8.0f;
  std::vector<float> sh(kMaxShCoeffs * 3, 0.0f), ex(extra::kCount);
  sh[0] = (0.8f - 0.5f) / 0.28209479f;
  sh[1] = (0.3f - 0.5f) / 0.28209479f;
  sh[2] = (0.5f - 0.5f) / 0.28209479f;
  const float act[extra::kCount] = {0.1f, 0.2f, 0.3f, 0.04f, 0.05f, 0.06f, 0.7f, 0.2f, 0.9f};
  for (int k = 0; k < extra::kCount; ++k) ex[k] = std::log(act[k] / (1 - act[k]));
  m.tensor(Param::Position).value.upload(pos, 3);
  m.tensor(Param::LogScale).value.upload(ls, 3);
  m.tensor(Param::Rotation).value.upload(rot, 4);
  m.tensor(Param::OpacityLogit).value.upload(&op, 1);
  m.tensor(Param::Sh).value.upload(sh.data(), sh.size());
  m.tensor(Param::ExtraLogit).value.upload(ex.data(), ex.size());
  const Camera cam = top_camera(16, 2.0f);
  const MapSet maps = render_removed_maps(m, cam, RasterSettings{});
  const std::size_t p = 8 * 16 + 8;
  EXPECT_NEAR(maps.depth.pixels[p], 2.0f, 0.01f);
  EXPECT_NEAR(maps.rgb.pixels[p * 3 + 0], 0.8f, 0.01f);
  EXPECT_NEAR(maps.rgb.pixels[p * 3 + 1], 0.3f, 0.01f);
  const float* n = &maps.normal.pixels[p * 3];
  EXPECT_NEAR(n[2], -1.0f, 1e-3f);  // facing the camera
  EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0f, 1e-5f);
  EXPECT_NEAR(maps.diffuse.pixels[p * 3 + 1], 0.2f, 1e-3f);
  EXPECT_NEAR(maps.fresnel.pixels[p * 3 + 2], 0.06f, 1e-3f);
  EXPECT_NEAR(maps.roughness.pixels[p], 0.7f, 1e-3f);
  EXPECT_NEAR(maps.region.pixels[p], 0.2f, 1e-3f);
}

}  // namespace
}  // namespace goris
