// Errors of recovered normals and materials against an intrinsic ground truth (train/intrinsic/intrinsic_accuracy.h):
// a flat floor of Gaussians with known roughness and F0, compared with true normals that are exact or tilted
// by a known angle; and the glossy material reference read from a `goris synth` scene.json.
#include <cmath>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_selection_scene.h"
#include "train/intrinsic/intrinsic_accuracy.h"
#include "train/intrinsic/material_separation.h"
#include "train/radiance/raster_renderer.h"

using namespace goris;
namespace fs = std::filesystem;

namespace {

// A floor (z = 0) of flat Gaussians with roughness 0.3 and F0 (0.6, 0.5, 0.4).
GaussianModel floor_model() {
  test::TestGaussian proto;
  proto.scale = 0.08f;
  proto.opacity = 0.99f;
  GaussianModel m = test::make_model(test::grid({0, 0, 0}, 16, 16, 1, 0.1f, proto));
  for (std::size_t i = 0; i < m.count(); ++i) {
    m.values(Param::LogScale)[3 * i + 2] = std::log(0.002f);
    float* e = m.values(Param::ExtraLogit) + extra::kCount * i;
    e[extra::kRoughness] = test::logit_of(0.3f);
    for (int c = 0; c < 3; ++c) e[extra::kFresnel + c] = test::logit_of(0.6f - 0.1f * float(c));
  }
  return m;
}

// One view from above at an angle; its glossy mask is everything, its true normal world +z turned by
// `tilt_deg` about the world x axis, in camera space and facing the camera.
TrainView view_with_truth(float tilt_deg) {
  TrainView v;
  v.name = "v";
  v.camera = test::look_at({0.3f, -1.2f, 1.5f}, {0, 0, 0}, 64, 64, 60.0f);
  const std::size_t hw = 64 * 64;
  v.glossy_mask.assign(hw, 1.0f);
  const float a = glm::radians(tilt_deg);
  glm::vec3 n = v.camera.R * glm::vec3(0.0f, -std::sin(a), std::cos(a));
  if (n.z > 0) n = -n;  // facing the camera (OpenCV: the camera looks along +z)
  v.normal_prior.resize(3 * hw);
  for (std::size_t p = 0; p < hw; ++p)
    for (int c = 0; c < 3; ++c) v.normal_prior[c * hw + p] = n[c];
  return v;
}

}  // namespace

TEST(IntrinsicAccuracy, NormalAngleRoughnessAndF0OfAKnownFloor) {
  GaussianModel m = floor_model();
  const RasterSettings raster = RasterRenderer::settings_for(TrainConfig{});
  GlossyMaterialReference ref;
  ref.roughness = 0.1f;
  ref.f0 = glm::vec3(0.6f, 0.5f, 0.4f);
  const IntrinsicAccuracy exact = measure_intrinsic_accuracy(m.view(true), {view_with_truth(0.0f)}, raster, Device::CPU, ref);
  EXPECT_EQ(exact.views, 1u);
  EXPECT_GT(exact.pixels, 500u);
  EXPECT_LT(exact.normal_mean_deg, 1.0);
  EXPECT_NEAR(exact.roughness_mean, 0.3, 0.01);  // alpha-normalised: the blend of equal values
  EXPECT_NEAR(exact.roughness_mae, 0.2, 0.01);
  EXPECT_NEAR(exact.f0_mean.y, 0.5, 0.01);
  EXPECT_LT(exact.f0_mae, 0.01);

  const IntrinsicAccuracy tilted = measure_intrinsic_accuracy(m.view(true), {view_with_truth(20.0f)}, raster, Device::CPU, ref);
  EXPECT_NEAR(tilted.normal_mean_deg, 20.0, 1.0);
  EXPECT_NEAR(tilted.normal_median_deg, 20.0, 1.0);

  // No glossy pixel, or no true normal: an error, not a zero.
  TrainView none = view_with_truth(0.0f);
  none.glossy_mask.assign(none.glossy_mask.size(), 0.0f);
  EXPECT_THROW(measure_intrinsic_accuracy(m.view(true), {none}, raster, Device::CPU, ref), Error);
  TrainView no_truth = view_with_truth(0.0f);
  no_truth.normal_prior.clear();
  EXPECT_THROW(measure_intrinsic_accuracy(m.view(true), {no_truth}, raster, Device::CPU, ref), Error);
}

TEST(IntrinsicAccuracy, GlossyReferenceFromASynthScene) {
  const fs::path dir = test::scratch_dir("intrinsic_accuracy_scene");
  auto write = [&](const char* text) {
    std::ofstream(dir / "scene.json") << text;
    return glossy_reference_from_scene(dir / "scene.json");
  };
  // A metal table (F0 = its colour) and a rough, non-glossy object.
  auto r = write(R"({"objects": [
      {"glossy": true, "material": {"color": [0.9, 0.8, 0.7], "metallic": 1.0, "roughness": 0.11, "specular": 0.5}},
      {"glossy": false, "material": {"color": [0.1, 0.2, 0.3], "metallic": 0.0, "roughness": 0.7, "specular": 0.5}}]})");
  ASSERT_TRUE(r.has_value());
  EXPECT_FLOAT_EQ(r->roughness, 0.11f);
  EXPECT_NEAR(r->f0.x, 0.9f, 1e-6f);
  // A dielectric glossy surface: F0 = 0.08 x specular.
  r = write(R"({"objects": [{"glossy": true, "material": {"color": [0.9, 0.8, 0.7], "metallic": 0.0, "roughness": 0.2, "specular": 0.5}}]})");
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->f0.y, 0.04f, 1e-6f);
  // Two different glossy materials: no single reference; none at all: none.
  EXPECT_FALSE(write(R"({"objects": [
      {"glossy": true, "material": {"roughness": 0.1}}, {"glossy": true, "material": {"roughness": 0.4}}]})").has_value());
  EXPECT_FALSE(write(R"({"objects": []})").has_value());
  EXPECT_FALSE(glossy_reference_from_scene(dir / "missing.json").has_value());
  std::ofstream(dir / "bad.json") << "{ not json";
  EXPECT_THROW(glossy_reference_from_scene(dir / "bad.json"), Error);
}

TEST(MaterialSeparation, ProbabilityGreaterCountsPairsAndTiesHalf) {
  EXPECT_DOUBLE_EQ(probability_greater({0.5f, 0.6f}, {0.1f, 0.2f}), 1.0);
  EXPECT_DOUBLE_EQ(probability_greater({0.1f, 0.2f}, {0.5f, 0.6f}), 0.0);
  EXPECT_DOUBLE_EQ(probability_greater({0.3f}, {0.3f}), 0.5);
  // 0.25 beats {0.1, 0.2}, ties nothing, loses to 0.3: 2 of 3; 0.1 ties 0.1: 0.5 of 3.
  EXPECT_NEAR(probability_greater({0.25f, 0.1f}, {0.1f, 0.2f, 0.3f}), (2.0 + 0.5) / 6.0, 1e-12);
  EXPECT_THROW(probability_greater({}, {0.1f}), Error);
}

TEST(MaterialSeparation, GlossyFloorAgainstARoughBlock) {
  // The floor (roughness 0.3, F0 0.5 mean) is glossy in the mask's left half only; the right half counts
  // as "rest". Then the right half's Gaussians get roughness 0.8: roughness alone separates the halves.
  GaussianModel m = floor_model();
  const RasterSettings raster = RasterRenderer::settings_for(TrainConfig{});
  TrainView v = view_with_truth(0.0f);
  v.normal_prior.clear();
  const int w = v.camera.width, h = v.camera.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v.glossy_mask[std::size_t(y) * w + x] = x < w / 2 ? 1.0f : 0.0f;
  const MaterialSeparation same = measure_material_separation(m.view(true), {v}, raster, Device::CPU);
  EXPECT_EQ(same.views, 1u);
  EXPECT_GT(same.glossy.pixels, 200u);
  EXPECT_GT(same.rest.pixels, 200u);
  EXPECT_NEAR(same.glossy.roughness_median, 0.3, 0.01);
  EXPECT_NEAR(same.rest.roughness_median, 0.3, 0.01);
  EXPECT_NEAR(same.glossy.f0_median, 0.5, 0.01);
  EXPECT_GT(same.roughness_auc, 0.2);
  EXPECT_LT(same.roughness_auc, 0.8);

  // Which Gaussians land in the right half: project the centres with the view's camera.
  for (std::size_t i = 0; i < m.count(); ++i) {
    const glm::vec3 c(m.values(Param::Position)[3 * i], m.values(Param::Position)[3 * i + 1],
                      m.values(Param::Position)[3 * i + 2]);
    const glm::vec3 cam = v.camera.to_camera(c);
    if (cam.z > 0 && v.camera.project_camera(cam).x >= float(w / 2))
      m.values(Param::ExtraLogit)[extra::kCount * i + extra::kRoughness] = test::logit_of(0.8f);
  }
  const MaterialSeparation split = measure_material_separation(m.view(true), {v}, raster, Device::CPU);
  EXPECT_NEAR(split.glossy.roughness_median, 0.3, 0.02);
  EXPECT_NEAR(split.rest.roughness_median, 0.8, 0.02);
  EXPECT_GT(split.roughness_auc, 0.9);

  // No glossy pixel: an error, not a number.
  TrainView none = v;
  none.glossy_mask.assign(none.glossy_mask.size(), 0.0f);
  EXPECT_THROW(measure_material_separation(m.view(true), {none}, raster, Device::CPU), Error);
}
