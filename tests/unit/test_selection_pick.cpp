// Click picking: the Gaussian with the largest blending weight along the pixel's ray, its hit point and
// depth; background pixels report no hit.
#include <gtest/gtest.h>

#include <vector>

#include "core/util/error.h"
#include "removal/selection/selection_pick.h"
#include "render/trace/gaussian_tracer.h"
#include "test_selection_scene.h"

namespace goris {
namespace {

using test::TestGaussian;

// Camera at the origin looking down +z; the centre pixel's ray runs along the z axis.
Camera axis_camera() { return test::look_at({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 64, 64, 64.0f); }

TEST(SelectionPick, FrontGaussianWinsOnARay) {
  // The back Gaussian comes first in the model, so the index order cannot give the answer away.
  const GaussianModel m = test::make_model({TestGaussian{{0.0f, 0.0f, 5.0f}, 0.2f, 0.9f},
                                            TestGaussian{{0.0f, 0.0f, 3.0f}, 0.2f, 0.9f}});
  const Camera cam = axis_camera();
  const PickResult p = pick_gaussian(m, cam, 32, 32);
  ASSERT_TRUE(p.hit);
  EXPECT_EQ(p.gaussian, 1u);
  EXPECT_EQ(p.blended, 2);
  EXPECT_NEAR(p.depth, 3.0f, 0.01f);
  EXPECT_NEAR(p.distance, 3.0f, 0.01f);
  EXPECT_NEAR(p.point.z, 3.0f, 0.01f);
  EXPECT_NEAR(p.point.x, 0.0f, 0.05f);
  // Weight of the front one: its alpha at the closest approach (almost through its centre) times T = 1.
  EXPECT_NEAR(p.weight, 0.9f, 0.02f);
  EXPECT_NEAR(p.ray_alpha, 1.0f - 0.1f * 0.1f, 0.02f);

  // The same ray through the tracer: the same opacity along it (picking shares its hit maths).
  GaussianModel mm = test::make_model({TestGaussian{{0.0f, 0.0f, 5.0f}, 0.2f, 0.9f},
                                       TestGaussian{{0.0f, 0.0f, 3.0f}, 0.2f, 0.9f}});
  GaussianTracer tracer(Device::CPU);
  tracer.build(mm.view(false));
  const glm::vec3 o = cam.center(), d = cam.ray_direction(32.5f, 32.5f);
  float alpha = 0.0f, depth = 0.0f;
  tracer.trace(TraceRays{&o.x, &d.x, 1, 0.0f}, TraceOutputs{nullptr, &depth, &alpha, nullptr, nullptr});
  EXPECT_NEAR(alpha, p.ray_alpha, 1e-6f);
}

TEST(SelectionPick, LargestWeightNotFirstHit) {
  // A faint Gaussian in front (alpha 0.05) does not hide an opaque one behind it.
  const GaussianModel m = test::make_model({TestGaussian{{0.0f, 0.0f, 3.0f}, 0.2f, 0.05f},
                                            TestGaussian{{0.0f, 0.0f, 5.0f}, 0.2f, 0.9f}});
  const PickResult p = pick_gaussian(m, axis_camera(), 32, 32);
  ASSERT_TRUE(p.hit);
  EXPECT_EQ(p.gaussian, 1u);
  EXPECT_NEAR(p.weight, 0.95f * 0.9f, 0.05f);  // less the Gaussian falloff 0.03 off the ray's centre
  EXPECT_NEAR(p.depth, 5.0f, 0.01f);
}

TEST(SelectionPick, BackgroundIsNoHitNotAnError) {
  const GaussianModel m = test::make_model({TestGaussian{{0.0f, 0.0f, 3.0f}, 0.2f, 0.9f}});
  const Camera cam = axis_camera();
  const PickResult corner = pick_gaussian(m, cam, 0, 0);
  EXPECT_FALSE(corner.hit);
  EXPECT_EQ(corner.blended, 0);
  EXPECT_EQ(corner.ray_alpha, 0.0f);
  // Behind the camera is not "under the pixel" either.
  const GaussianModel behind = test::make_model({TestGaussian{{0.0f, 0.0f, -3.0f}, 0.2f, 0.9f}});
  EXPECT_FALSE(pick_gaussian(behind, cam, 32, 32).hit);
  // Only a very faint Gaussian on the ray: below min_weight, so background.
  const GaussianModel faint = test::make_model({TestGaussian{{0.0f, 0.0f, 3.0f}, 0.2f, 0.008f}});
  const PickResult pf = pick_gaussian(faint, cam, 32, 32);
  EXPECT_FALSE(pf.hit);
  EXPECT_EQ(pf.blended, 1);
  PickSettings lenient;
  lenient.min_weight = 0.001f;
  EXPECT_TRUE(pick_gaussian(faint, cam, 32, 32, lenient).hit);
  // No Gaussians at all.
  EXPECT_FALSE(pick_gaussian(test::make_model({}), cam, 32, 32).hit);
}

TEST(SelectionPick, PickerAnswersManyClicksAndRejectsBadInput) {
  // A row of Gaussians across the view: each pixel column picks the one in front of it.
  std::vector<TestGaussian> row;
  for (int i = 0; i < 5; ++i) row.push_back(TestGaussian{{-1.0f + 0.5f * float(i), 0.0f, 4.0f}, 0.1f, 0.9f});
  const GaussianModel m = test::make_model(row);
  const Camera cam = axis_camera();
  const GaussianPicker picker(m);
  EXPECT_EQ(picker.count(), 5u);
  for (int i = 0; i < 5; ++i) {
    const glm::vec2 uv = cam.project_camera(cam.to_camera(row[std::size_t(i)].pos));
    const PickResult p = picker.pick(cam, uv.x, uv.y);
    ASSERT_TRUE(p.hit) << i;
    EXPECT_EQ(p.gaussian, std::uint32_t(i));
  }
  const PickResult ray = picker.pick_ray({0.5f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f});  // any direction length
  EXPECT_TRUE(ray.hit);
  EXPECT_EQ(ray.gaussian, 3u);
  EXPECT_NEAR(ray.distance, 4.0f, 0.01f);
  EXPECT_THROW(picker.pick(cam, -1.0f, 10.0f), Error);
  EXPECT_THROW(picker.pick(cam, 10.0f, 64.0f), Error);
  EXPECT_THROW(picker.pick_ray({0, 0, 0}, {0, 0, 0}), Error);
  GaussianModel bad = test::make_model(row);
  bad.values(Param::Rotation)[0] = 0.0f;  // a zero quaternion
  EXPECT_THROW(GaussianPicker{bad}, Error);
}

}  // namespace
}  // namespace goris
