// Lifting inpainted reference views to new Gaussians: positions from the camera and depth (checked
// against an independent ray construction), the stride grid and count, scale/rotation from a nearby
// existing Gaussian or the pixel footprint, colour and material logits, Adam state, the 3D filter, the
// automatic stride, the reference points and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/lift/lift.h"

namespace goris {
namespace {

constexpr int kW = 32, kH = 32;
constexpr float kF = 50.0f;

float logit(float p) { return std::log(p / (1.0f - p)); }

// A tilted camera 3 units from the origin (not axis-aligned, so R's layout matters).
Camera test_camera() {
  const glm::vec3 eye(1.0f, -2.0f, 2.2f), at(0.1f, 0.2f, 0.0f);
  const glm::vec3 fwd = glm::normalize(at - eye), right = glm::normalize(glm::cross(fwd, glm::vec3(0, 0, 1)));
  const glm::vec3 down = glm::cross(fwd, right);
  Camera c;
  c.width = kW;
  c.height = kH;
  c.fx = kF;
  c.fy = 1.1f * kF;
  c.cx = 15.3f;
  c.cy = 16.9f;
  for (int k = 0; k < 3; ++k) {
    c.R[k][0] = right[k];
    c.R[k][1] = down[k];
    c.R[k][2] = fwd[k];
  }
  c.t = -(c.R * eye);
  return c;
}

// Depth z = 2 + 0.01 x + 0.02 y, rgb / materials with known values, normals facing the camera.
MapSet test_maps(bool materials) {
  MapSet m;
  m.depth = Image(kW, kH, 1);
  m.rgb = Image(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t p = std::size_t(y) * kW + x;
      m.depth.pixels[p] = 2.0f + 0.01f * x + 0.02f * y;
      m.rgb.pixels[p * 3 + 0] = 0.8f;
      m.rgb.pixels[p * 3 + 1] = 0.25f;
      m.rgb.pixels[p * 3 + 2] = float(x) / kW;
    }
  if (materials) {
    m.diffuse = Image(kW, kH, 3);
    m.fresnel = Image(kW, kH, 3);
    m.roughness = Image(kW, kH, 1);
    m.region = Image(kW, kH, 1);
    m.normal = Image(kW, kH, 3);
    for (std::size_t p = 0; p < m.depth.pixel_count(); ++p) {
      for (int c = 0; c < 3; ++c) {
        m.diffuse.pixels[p * 3 + c] = 0.1f * (c + 1);
        m.fresnel.pixels[p * 3 + c] = 0.04f;
        m.normal.pixels[p * 3 + c] = c == 2 ? -1.0f : 0.0f;
      }
      m.roughness.pixels[p] = 0.3f;
      m.region.pixels[p] = 0.0f;  // glossy: clamped before the logit
    }
  }
  return m;
}

Mask square(int x0, int y0, int s) {
  Mask m(kW, kH);
  for (int y = y0; y < y0 + s; ++y)
    for (int x = x0; x < x0 + s; ++x) m.set(x, y, true);
  return m;
}

// A model with the given Gaussians (position, log scale, rotation), opacity 0.5, Adam moments 7.
GaussianModel model_with(const std::vector<glm::vec3>& pos, const std::vector<glm::vec3>& log_scale,
                         const std::vector<glm::vec4>& rot) {
  GaussianModel m(Device::CPU);
  m.allocate(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      m.tensor(Param::Position).value[i * 3 + k] = pos[i][k];
      m.tensor(Param::LogScale).value[i * 3 + k] = log_scale[i][k];
    }
    for (int k = 0; k < 4; ++k) m.tensor(Param::Rotation).value[i * 4 + k] = rot[i][k];
    m.tensor(Param::OpacityLogit).value[i] = 0.0f;
  }
  for (int k = 0; k < kMaxShCoeffs * 3 * int(pos.size()); ++k) m.tensor(Param::Sh).value[k] = 0.0f;
  for (int k = 0; k < extra::kCount * int(pos.size()); ++k) m.tensor(Param::ExtraLogit).value[k] = 0.0f;
  for (int p = 0; p < kParamCount; ++p)
    for (std::size_t k = 0; k < m.tensor(Param(p)).adam_m.size(); ++k) m.tensor(Param(p)).adam_m[k] = 7.0f;
  return m;
}

// The world point of pixel (x, y) at camera depth z, built differently from back_project(): the unit ray
// through the pixel centre, scaled so that its component along the optical axis is z.
glm::vec3 expected_point(const Camera& c, int x, int y, float z) {
  const glm::vec3 d = c.ray_direction(float(x) + 0.5f, float(y) + 0.5f);
  return c.center() + d * (z / glm::dot(d, c.forward()));
}

TEST(Lift, PositionsCountAndAttributes) {
  const Camera cam = test_camera();
  const MapSet maps = test_maps(true);
  const Mask mask = square(8, 8, 16);
  GaussianModel model = model_with({{50, 50, 50}}, {{-1, -1, -1}}, {{1, 0, 0, 0}});  // far from everything
  LiftSettings s;
  s.stride = 2;
  const LiftResult r = lift_reference_views(model, {LiftView{4, cam, &mask, &maps}}, s);

  ASSERT_EQ(r.first_new, 1u);
  ASSERT_EQ(r.added, 64u);  // 8 x 8 pixels with even x and y in [8, 24)
  ASSERT_EQ(model.count(), 65u);
  EXPECT_EQ(r.stride, (std::vector<int>{2}));
  EXPECT_EQ(r.from_neighbour, 0u);
  const auto pos = model.tensor(Param::Position).value.to_host();
  const auto ls = model.tensor(Param::LogScale).value.to_host();
  const auto rot = model.tensor(Param::Rotation).value.to_host();
  const auto op = model.tensor(Param::OpacityLogit).value.to_host();
  const auto sh = model.tensor(Param::Sh).value.to_host();
  const auto ex = model.tensor(Param::ExtraLogit).value.to_host();
  std::size_t i = 1;
  for (int y = 8; y < 24; y += 2)
    for (int x = 8; x < 24; x += 2, ++i) {
      const float z = 2.0f + 0.01f * x + 0.02f * y;
      const glm::vec3 e = expected_point(cam, x, y, z);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(pos[i * 3 + k], e[k], 1e-5f) << "pixel " << x << "," << y;
      // No neighbour: isotropic, one sample spacing (2 pixels at depth z) wide.
      const float spacing = 2.0f * z / (0.5f * (cam.fx + cam.fy));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(ls[i * 3 + k], std::log(spacing), 1e-5f);
      EXPECT_EQ(rot[i * 4 + 0], 1.0f);
      EXPECT_NEAR(op[i], logit(0.1f), 1e-6f);
      EXPECT_NEAR(sh[i * 48 + 0], (0.8f - 0.5f) / 0.28209479f, 1e-5f);
      EXPECT_NEAR(sh[i * 48 + 2], (float(x) / kW - 0.5f) / 0.28209479f, 1e-5f);
      for (int k = 3; k < 48; ++k) EXPECT_EQ(sh[i * 48 + k], 0.0f);
      EXPECT_NEAR(ex[i * 9 + extra::kDiffuse + 1], logit(0.2f), 1e-5f);
      EXPECT_NEAR(ex[i * 9 + extra::kFresnel], logit(0.04f), 1e-5f);
      EXPECT_NEAR(ex[i * 9 + extra::kRoughness], logit(0.3f), 1e-5f);
      EXPECT_NEAR(ex[i * 9 + extra::kRegion], logit(1e-3f), 1e-4f);
      EXPECT_NEAR(ex[i * 9 + extra::kLabel], logit(0.01f), 1e-5f);
    }
  // Adam state: kept for the old Gaussian, zero for the new ones; gradients zero.
  const auto m0 = model.tensor(Param::Position).adam_m.to_host();
  EXPECT_EQ(m0[0], 7.0f);
  EXPECT_EQ(m0[3], 0.0f);
  EXPECT_EQ(m0.back(), 0.0f);
  for (float g : model.tensor(Param::Sh).grad.to_host()) ASSERT_EQ(g, 0.0f);

  // Reference points: every masked pixel, with the view index, colour, materials and world normal.
  const ReferencePoints& ref = r.points;
  ASSERT_EQ(ref.size(), 256u);
  EXPECT_EQ(ref.view[0], 4);
  EXPECT_EQ(ref.pixel[17], glm::ivec2(9, 9));
  const glm::vec3 e = expected_point(cam, 9, 9, 2.0f + 0.09f + 0.18f);
  EXPECT_NEAR(glm::length(ref.position[17] - e), 0.0f, 1e-5f);
  EXPECT_NEAR(ref.color[17].z, 9.0f / kW, 1e-6f);
  EXPECT_NEAR(ref.roughness[17], 0.3f, 1e-6f);
  EXPECT_NEAR(glm::length(ref.normal[17] - (-cam.forward())), 0.0f, 1e-5f);  // camera -z in world
}

TEST(Lift, ScaleAndRotationFromANearbyGaussian) {
  const Camera cam = test_camera();
  const MapSet maps = test_maps(false);
  const Mask mask = square(8, 8, 16);
  const float z = 2.0f + 0.01f * 10 + 0.02f * 12;
  const glm::vec3 near_pixel = expected_point(cam, 10, 12, z) + glm::vec3(0.01f, 0.0f, 0.0f);
  GaussianModel model =
      model_with({near_pixel}, {{-3.0f, -4.0f, -5.0f}}, {{0.6f, 0.8f, 0.0f, 0.0f}});
  LiftSettings s;
  s.stride = 2;
  const LiftResult r = lift_reference_views(model, {LiftView{0, cam, &mask, &maps}}, s);
  ASSERT_EQ(r.added, 64u);
  const auto ls = model.tensor(Param::LogScale).value.to_host();
  const auto rot = model.tensor(Param::Rotation).value.to_host();
  const auto ex = model.tensor(Param::ExtraLogit).value.to_host();
  // Pixel (10, 12) is sample 1 + (12 - 8) / 2 * 8 + (10 - 8) / 2 = 18 of the model (index 0 is the old one).
  const std::size_t i = 1 + 2 * 8 + 1;
  EXPECT_EQ(ls[i * 3 + 0], -3.0f);
  EXPECT_EQ(ls[i * 3 + 2], -5.0f);
  EXPECT_EQ(rot[i * 4 + 0], 0.6f);
  EXPECT_EQ(rot[i * 4 + 1], 0.8f);
  // Far corner sample (22, 22): more than 3 spacings away, so the footprint is used.
  const std::size_t far = 1 + 7 * 8 + 7;
  EXPECT_EQ(rot[far * 4 + 0], 1.0f);
  EXPECT_GT(ls[far * 3 + 0], -3.0f);
  EXPECT_GT(r.from_neighbour, 0u);
  EXPECT_LT(r.from_neighbour, 64u);
  // Without material maps the materials are 0.5 (logit 0).
  EXPECT_NEAR(ex[i * 9 + extra::kDiffuse], 0.0f, 1e-6f);
  EXPECT_NEAR(ex[i * 9 + extra::kRegion], 0.0f, 1e-6f);
  EXPECT_EQ(r.points.normal[0], glm::vec3(0.0f));
}

TEST(Lift, AutomaticStrideMatchesTheNeighboursScale) {
  // Existing Gaussians on the surface the depth map describes, each 0.2 wide in-plane (the mean of the
  // two largest scales).
  const Camera cam = test_camera();
  const MapSet maps = test_maps(false);
  const Mask mask = square(4, 4, 24);
  std::vector<glm::vec3> pos, scale;
  std::vector<glm::vec4> rot;
  for (int y = 0; y < kH; y += 2)
    for (int x = 0; x < kW; x += 2) {
      pos.push_back(expected_point(cam, x, y, 2.0f + 0.01f * x + 0.02f * y));
      scale.emplace_back(std::log(0.2f), std::log(0.2f), std::log(0.001f));
      rot.emplace_back(1, 0, 0, 0);
    }
  GaussianModel model = model_with(pos, scale, rot);
  const LiftResult r = lift_reference_views(model, {LiftView{0, cam, &mask, &maps}});
  // Median depth over the mask ~2.48, f = 52.5: footprint 0.0472; 0.2 / 0.0472 = 4.2 -> 4.
  EXPECT_EQ(r.stride, (std::vector<int>{4}));
  EXPECT_EQ(r.added, 36u);  // x, y in {4, 8, ..., 24}
  // With no existing Gaussian the stride is 1.
  GaussianModel empty(Device::CPU);
  empty.allocate(0);
  const LiftResult r1 = lift_reference_views(empty, {LiftView{0, cam, &mask, &maps}});
  EXPECT_EQ(r1.stride, (std::vector<int>{1}));
  EXPECT_EQ(r1.added, 24u * 24u);
  EXPECT_EQ(empty.count(), 24u * 24u);
}

TEST(Lift, SmallMasksInvalidDepthAndFilter) {
  const Camera cam = test_camera();
  MapSet maps = test_maps(false);
  maps.depth.pixels[9 * kW + 9] = 0.0f;  // no depth at one grid pixel
  GaussianModel model = model_with({{50, 50, 50}}, {{-1, -1, -1}}, {{1, 0, 0, 0}});
  model.filter3d_var = Buffer<float>(std::vector<float>{0.5f}, Device::CPU);
  Mask tiny(kW, kH);
  tiny.set(5, 7, true);  // off the stride-4 grid
  const Mask two = square(8, 8, 2);  // holds (8, 8) on the grid... and (9, 9) without depth
  LiftSettings s;
  s.stride = 4;
  const LiftResult r = lift_reference_views(model, {LiftView{0, cam, &tiny, &maps}, LiftView{1, cam, &two, &maps}}, s);
  EXPECT_EQ(r.added, 2u);  // (5, 7) as the tiny mask's only pixel, (8, 8) from the grid
  EXPECT_EQ(r.points.size(), 1u + 3u);  // every pixel with a depth
  ASSERT_EQ(model.filter3d_var.size(), 3u);
  EXPECT_EQ(model.filter3d_var[0], 0.5f);
  const float z = 2.0f + 0.05f + 0.14f;
  EXPECT_NEAR(model.filter3d_var[1], 0.2f * (z / kF) * (z / kF), 1e-7f);
  const auto pos = model.tensor(Param::Position).value.to_host();
  EXPECT_NEAR(glm::length(glm::vec3(pos[3], pos[4], pos[5]) - expected_point(cam, 5, 7, z)), 0.0f, 1e-5f);
}

TEST(Lift, BadInput) {
  const Camera cam = test_camera();
  MapSet no_rgb = test_maps(false);
  no_rgb.rgb = Image();
  const Mask mask = square(8, 8, 4);
  GaussianModel model = model_with({{0, 0, 0}}, {{-1, -1, -1}}, {{1, 0, 0, 0}});
  EXPECT_THROW(lift_reference_views(model, {LiftView{0, cam, &mask, &no_rgb}}), Error);
  const MapSet maps = test_maps(false);
  const Mask small(16, 16);
  EXPECT_THROW(lift_reference_views(model, {LiftView{0, cam, &small, &maps}}), Error);
  EXPECT_THROW(lift_reference_views(model, {LiftView{0, cam, nullptr, &maps}}), Error);
  MapSet bad_rough = test_maps(false);
  bad_rough.roughness = Image(kW, kH, 3);
  EXPECT_THROW(lift_reference_views(model, {LiftView{0, cam, &mask, &bad_rough}}), Error);
  EXPECT_EQ(model.count(), 1u);  // nothing appended on error

  GaussianRows rows;
  rows.count = 2;
  rows.position.resize(6);
  EXPECT_THROW(append_gaussians(model, rows), Error);
}

}  // namespace
}  // namespace goris
