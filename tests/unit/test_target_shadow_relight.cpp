// The target's cast shadow relit in rendered views of a Gaussian floor (removal/shadow/target_shadow_scene.h):
// relight_target_shadow() as `goris remove` runs it - the light found from the photos or from the model's
// colour, near the environment's light over a dielectric only, and the other objects' shadows left as they are.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include "core/scene/gaussians.h"
#include "removal/shadow/target_shadow.h"
#include "removal/shadow/target_shadow_scene.h"
#include "render/raster/rasterizer.h"
#include "tests/support/test_support.h"
#include "tests/unit/target_shadow_test_scene.h"
#include "tests/unit/test_selection_scene.h"

namespace goris {
namespace {

using namespace shadow_test;

// A Gaussian floor over [-1.5, 1.5]^2 at z = 0, then the ball's 150 centres standing on it (the target).
constexpr std::size_t kFloorGaussians = 625;
std::vector<test::TestGaussian> floor_and_ball(std::mt19937& rng) {
  std::vector<test::TestGaussian> gs;
  for (int y = 0; y < 25; ++y)
    for (int x = 0; x < 25; ++x) gs.push_back({{-1.5f + 0.125f * x, -1.5f + 0.125f * y, 0.0f}, 0.07f, 0.95f, glm::vec3(0.7f), 0.05f});
  for (int i = 0; i < 150; ++i)
    gs.push_back({glm::vec3(0.0f, 0.0f, 0.45f) + 0.28f * in_unit_ball(rng), 0.06f, 0.95f, {0.8f, 0.2f, 0.2f}, 0.95f});
  return gs;
}

// That floor as a support plane made by hand (z = 0), reaching everywhere.
ShadowGeometry floor_plane() {
  ShadowGeometry floor;
  floor.found = true;
  floor.plane.found = true;
  floor.plane.tolerance = 0.03;
  floor.reach = 100.0;
  return floor;
}

// View k of eight 64 px views on a ring around the floor.
TrainView ring_view(int k) {
  const float a = 0.785398f * float(k);
  TrainView v;
  v.name = "v" + std::to_string(k);
  v.camera = test::look_at({3.0f * std::cos(a), 3.0f * std::sin(a), 2.5f}, {0.0f, 0.0f, 0.1f}, 64, 64, 55.0f);
  return v;
}

// View k of the ring with the model's render as its image (unshaded), and the floor's pixels in it.
PlanePixels rendered_ring_view(GaussianModel& model, int k, TrainView& v) {
  v = ring_view(k);
  const RasterOutput r = rasterize(model.view(false), v.camera, RasterSettings{}, Device::CPU);
  v.image = r.gbuffer.color.to_host();
  return support_plane_pixels(v.camera, r.gbuffer.median_depth.to_host(), r.gbuffer.alpha.to_host(), floor_plane());
}

// The step `goris remove` runs, on views rendered from a Gaussian floor with a ball on it: the photos are
// the renders with the ball's shadow under a known light; relight_target_shadow() finds that light, writes
// the share images and gives back photos close to the unshaded renders.
TEST(TargetShadow, RelightTargetShadowOnRenderedViews) {
  std::mt19937 rng(4);
  const std::vector<test::TestGaussian> gs = floor_and_ball(rng);
  GaussianModel model = test::make_model(gs);
  SelectionMask target(gs.size(), 0);
  for (std::size_t i = kFloorGaussians; i < gs.size(); ++i) target[i] = 1;
  const TargetOccluder occ(model, target);

  // The floor's pixels in each view, shaded by the ball.
  const RasterSettings raster;
  std::vector<TrainView> views;
  std::vector<std::vector<float>> lit;
  std::vector<std::vector<std::uint8_t>> in_shadow;
  for (int k = 0; k < 8; ++k) {
    TrainView v;
    const PlanePixels px = rendered_ring_view(model, k, v);
    lit.push_back(v.image);
    std::vector<float> alpha(px.size());
    occ.function()(px.point, std::vector<glm::vec3>(px.size(), glm::vec3(kLight)), alpha);
    in_shadow.emplace_back(64 * 64, 0);
    for (std::size_t q = 0; q < px.size(); ++q)
      for (int c = 0; c < 3; ++c) {
        float& pixel = v.image[std::size_t(c) * 64 * 64 + px.pixel[q]];
        pixel = float(std::pow(std::pow(double(pixel), 2.2) * (1.0 - kStrength[c] * alpha[q]), 1.0 / 2.2));
        in_shadow.back()[px.pixel[q]] = alpha[q] > 0.5f;
      }
    views.push_back(std::move(v));
  }

  const std::filesystem::path out = test::scratch_dir("target_shadow_relight");
  const ShadowRelight r = relight_target_shadow(model, target, target, nullptr, views, raster, out);
  ASSERT_TRUE(r.fit.found) << r.fit.reason;
  EXPECT_LT(std::acos(std::clamp(glm::dot(r.fit.light_direction, kLight), -1.0, 1.0)) * 180.0 / 3.14159265, 8.0)
      << r.fit.reason;
  EXPECT_NEAR(r.fit.strength_luminance, 0.55, 0.15) << r.fit.reason;
  EXPECT_GT(r.relit_pixels, 50u);
  for (const TrainView& v : views) EXPECT_TRUE(std::filesystem::exists(out / (v.name + ".png"))) << v.name;
  double before = 0, after = 0;
  std::size_t shaded = 0;
  for (std::size_t k = 0; k < views.size(); ++k)
    for (std::size_t p = 0; p < 64 * 64; ++p) {
      if (!in_shadow[k][p]) continue;
      ++shaded;
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = std::size_t(c) * 64 * 64 + p;
        after += std::abs(views[k].image[i] - lit[k][i]);
        before += std::abs(float(std::pow(std::pow(double(lit[k][i]), 2.2) * (1.0 - kStrength[c]), 1.0 / 2.2)) - lit[k][i]);
      }
    }
  ASSERT_GT(shaded, 50u);
  EXPECT_LT(after, 0.35 * before) << shaded << " shaded pixels";
}


// Eight 64 px views on a ring around the floor, each image the model's render.
std::vector<TrainView> ring_of_views(GaussianModel& model, const RasterSettings& raster) {
  std::vector<TrainView> views;
  for (int k = 0; k < 8; ++k) {
    TrainView v = ring_view(k);
    v.image = rasterize(model.view(false), v.camera, raster, Device::CPU).gbuffer.color.to_host();
    views.push_back(std::move(v));
  }
  return views;
}

// A glossy floor: the ball's shadow is in the floor's own (diffuse) colour, and every photo shows instead a
// bright reflection that moves from view to view and hides it. Sampled from the photos the fit finds no
// light; sampled from the model's colour (what an intrinsic model renders as D) it finds the true one, and
// the photos are what it relights.
TEST(TargetShadow, ModelColourSamplesSeeAShadowTheReflectionsHide) {
  std::vector<test::TestGaussian> gs;
  for (int y = 0; y < 25; ++y)
    for (int x = 0; x < 25; ++x) {
      const glm::vec3 p(-1.5f + 0.125f * x, -1.5f + 0.125f * y, 0.0f);
      glm::vec3 c(0.7f);
      if (hits_ball(p, glm::vec3(kLight)))
        for (int k = 0; k < 3; ++k) c[k] = float(std::pow(std::pow(0.7, 2.2) * (1.0 - kStrength[k]), 1.0 / 2.2));
      gs.push_back({p, 0.07f, 0.95f, c, 0.05f});
    }
  std::mt19937 rng(4);
  for (int i = 0; i < 150; ++i)
    gs.push_back({kBall + kBallRadius * in_unit_ball(rng), 0.06f, 0.95f, {0.8f, 0.2f, 0.2f}, 0.95f});
  GaussianModel model = test::make_model(gs);
  SelectionMask target(gs.size(), 0);
  for (std::size_t i = 625; i < gs.size(); ++i) target[i] = 1;

  const RasterSettings raster;
  std::vector<TrainView> views = ring_of_views(model, raster);
  for (int k = 0; k < 8; ++k) {
    TrainView& v = views[std::size_t(k)];
    // The photo: the floor unshaded, with a bright band of reflection across it that each view sees elsewhere.
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const std::size_t p = std::size_t(y) * 64 + std::size_t(x);
        const float band = std::exp(-0.5f * std::pow((float(x + y) - 16.0f * float(k % 4) - 40.0f) / 6.0f, 2.0f));
        for (int c = 0; c < 3; ++c) {
          float& pixel = v.image[std::size_t(c) * 64 * 64 + p];
          if (pixel < 0.69f && pixel > 0.2f) pixel = 0.7f;  // the shadow is not in the photo
          pixel = std::min(1.0f, pixel + 0.3f * band);
        }
      }
  }
  const std::vector<TrainView> photos = views;

  std::vector<TrainView> by_photos = photos;
  const ShadowRelight from_photos = relight_target_shadow(model, target, target, nullptr, by_photos, raster, {});
  EXPECT_FALSE(from_photos.fit.found) << from_photos.fit.reason;

  std::vector<TrainView> by_model = photos;
  const ShadowRelight from_model =
      relight_target_shadow(model, target, target, nullptr, by_model, raster, {}, ShadowSampleColour::Model);
  ASSERT_TRUE(from_model.fit.found) << from_model.fit.reason;
  EXPECT_LT(std::acos(std::clamp(glm::dot(from_model.fit.light_direction, kLight), -1.0, 1.0)) * 180.0 / 3.14159265, 8.0)
      << from_model.fit.reason;
  // The photos are what gets relit: brighter where the model is shaded, never darker.
  double gained = 0;
  for (std::size_t k = 0; k < views.size(); ++k)
    for (std::size_t i = 0; i < photos[k].image.size(); ++i) {
      ASSERT_GE(by_model[k].image[i], photos[k].image[i] - 1e-6f);
      gained += by_model[k].image[i] - photos[k].image[i];
    }
  EXPECT_GT(gained, 10.0);
}

// An intrinsic model's floor whose colour holds the shadow of a high light under a grainy texture:
// the search over the whole sky finds nothing; given the model's environment, whose brightest region is that
// light, it is found near there - over a dielectric floor, not over a metal one.
TEST(TargetShadow, EnvironmentLightSearchedOverADielectricOnly) {
  const glm::dvec3 overhead = glm::normalize(glm::dvec3(0.45, 0.15, 1.0));
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> grain(-0.15f, 0.15f);
  std::vector<test::TestGaussian> gs;
  for (int y = 0; y < 25; ++y)
    for (int x = 0; x < 25; ++x) {
      const glm::vec3 p(-1.5f + 0.125f * x, -1.5f + 0.125f * y, 0.0f);
      glm::vec3 c(0.6f + grain(rng));
      if (hits_ball(p, glm::vec3(overhead)))
        for (int k = 0; k < 3; ++k) c[k] = float(std::pow(std::pow(double(c[k]), 2.2) * (1.0 - kStrength[k]), 1.0 / 2.2));
      gs.push_back({p, 0.07f, 0.95f, c, 0.05f});
    }
  for (int i = 0; i < 150; ++i)
    gs.push_back({kBall + kBallRadius * in_unit_ball(rng), 0.06f, 0.95f, {0.8f, 0.2f, 0.2f}, 0.95f});
  GaussianModel model = test::make_model(gs);
  SelectionMask target(gs.size(), 0);
  for (std::size_t i = 625; i < gs.size(); ++i) target[i] = 1;
  auto set_fresnel = [&](float f0) {
    float* ex = model.values(Param::ExtraLogit);
    for (std::size_t i = 0; i < 625; ++i)
      for (int c = 0; c < 3; ++c) ex[i * extra::kCount + extra::kFresnel + c] = test::logit_of(f0);
  };
  const RasterSettings raster;
  const std::vector<TrainView> views = ring_of_views(model, raster);
  // The environment at infinity: dim, with a lamp 15 degrees from the light.
  EnvironmentImage env;
  env.width = 128;
  env.equirect.assign(std::size_t(128) * 64 * 3, 0.05f);
  const glm::dvec3 lamp = glm::normalize(glm::dvec3(0.2, 0.0, 1.0));
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 128; ++i) {
      const double t = 3.14159265358979 * (j + 0.5) / 64, ph = 2 * 3.14159265358979 * (i + 0.5) / 128 - 3.14159265358979;
      const glm::dvec3 d(std::sin(t) * std::sin(ph), std::cos(t), std::sin(t) * std::cos(ph));
      if (glm::dot(d, lamp) > std::cos(0.1))
        for (int c = 0; c < 3; ++c) env.equirect[(std::size_t(j) * 128 + i) * 3 + c] = 10.0f;
    }

  set_fresnel(0.05f);
  std::vector<TrainView> blind = views;
  const ShadowRelight none = relight_target_shadow(model, target, target, nullptr, blind, raster, {}, ShadowSampleColour::Model);
  EXPECT_FALSE(none.fit.found) << none.fit.reason;
  std::vector<TrainView> told = views;
  const ShadowRelight found =
      relight_target_shadow(model, target, target, nullptr, told, raster, {}, ShadowSampleColour::Model, &env);
  ASSERT_TRUE(found.fit.found) << found.fit.reason;
  EXPECT_TRUE(found.fit.from_known_light) << found.fit.reason;
  // Within the soft shadow's cone (20 degrees) of the true light; the lamp itself is 15 degrees off.
  EXPECT_LT(std::acos(std::clamp(glm::dot(found.fit.light_direction, overhead), -1.0, 1.0)) * 180.0 / 3.14159265, 12.0)
      << found.fit.reason;
  EXPECT_GT(found.relit_pixels, 20u);

  set_fresnel(0.5f);
  std::vector<TrainView> metal = views;
  const ShadowRelight over_metal =
      relight_target_shadow(model, target, target, nullptr, metal, raster, {}, ShadowSampleColour::Model, &env);
  EXPECT_FALSE(over_metal.fit.found) << over_metal.fit.reason;
  EXPECT_NE(over_metal.fit.reason.find("a metal's colour is its reflections"), std::string::npos) << over_metal.fit.reason;
  EXPECT_EQ(over_metal.relit_pixels, 0u);
}

TEST(TargetShadow, BesideOthersTheRelitColourIsTheSceneWithoutTheTarget) {
  // For shares of the cone taken independently, relighting with the returned s turns the photo's light
  // 1 - k (1 - (1 - s_t)(1 - s_o)) into the light without the target, 1 - k s_o.
  for (double k : {0.3, 0.6, 0.97})
    for (float st : {0.0f, 0.25f, 0.7f, 1.0f})
      for (float so : {0.0f, 0.4f, 0.9f, 1.0f}) {
        const double photo = 1.0 - k * (1.0 - (1.0 - st) * (1.0 - so));
        const double s = shadow_fraction_beside_others(st, so, k);
        EXPECT_NEAR(photo / (1.0 - k * s), 1.0 - k * so, 1e-6) << k << " " << st << " " << so;
        EXPECT_GE(s, 0.0);
        EXPECT_LE(s, st + 1e-6);
      }
  EXPECT_FLOAT_EQ(shadow_fraction_beside_others(0.8f, 0.0f, 0.6), 0.8f);
  EXPECT_FLOAT_EQ(shadow_fraction_beside_others(0.8f, 1.0f, 0.6), 0.0f);
}

// The step `goris remove` runs, with another object between the light and half of the target's shadow: where
// both shade the floor, the photos keep the other's shadow after the relight (the scene without the target
// is still dark there); where only the target shades it, the floor is relit.
TEST(TargetShadow, RelightLeavesTheOtherObjectsShadow) {
  std::mt19937 rng(4);
  std::vector<test::TestGaussian> gs = floor_and_ball(rng);
  const std::size_t target_end = gs.size();
  // Above the floor on the light's side: its shadow covers the half of the ball's with x > -0.225.
  const glm::vec3 light(kLight);
  const glm::vec3 other_centre = glm::vec3(0.075f, 0.135f, 0.0f) + light * (0.95f / light.z);
  for (int i = 0; i < 120; ++i)
    gs.push_back({other_centre + 0.2f * in_unit_ball(rng), 0.05f, 0.95f, {0.2f, 0.8f, 0.2f}, 0.95f});
  GaussianModel model = test::make_model(gs);
  SelectionMask target(gs.size(), 0), other(gs.size(), 0);
  for (std::size_t i = kFloorGaussians; i < target_end; ++i) target[i] = 1;
  for (std::size_t i = target_end; i < gs.size(); ++i) other[i] = 1;
  const TargetOccluder by_target(model, target), by_other(model, other);

  const RasterSettings raster;
  std::vector<TrainView> views;
  std::vector<std::vector<float>> lit, truth, shaded;  // shaded: the photos
  std::vector<std::vector<std::uint8_t>> both, target_only;
  for (int k = 0; k < 8; ++k) {
    TrainView v;
    const PlanePixels px = rendered_ring_view(model, k, v);
    lit.push_back(v.image);
    const std::vector<glm::vec3> to_light(px.size(), light);
    std::vector<float> at(px.size()), ao(px.size());
    by_target.function()(px.point, to_light, at);
    by_other.function()(px.point, to_light, ao);
    std::vector<float> without = v.image;
    both.emplace_back(64 * 64, 0);
    target_only.emplace_back(64 * 64, 0);
    for (std::size_t q = 0; q < px.size(); ++q) {
      const double blocked = 1.0 - (1.0 - at[q]) * (1.0 - ao[q]);
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = std::size_t(c) * 64 * 64 + px.pixel[q];
        const double linear = std::pow(double(lit.back()[i]), 2.2);
        v.image[i] = float(std::pow(linear * (1.0 - kStrength[c] * blocked), 1.0 / 2.2));
        without[i] = float(std::pow(linear * (1.0 - kStrength[c] * ao[q]), 1.0 / 2.2));
      }
      both.back()[px.pixel[q]] = at[q] > 0.5f && ao[q] > 0.5f;
      target_only.back()[px.pixel[q]] = at[q] > 0.5f && ao[q] < 0.05f;
    }
    truth.push_back(std::move(without));
    shaded.push_back(v.image);
    views.push_back(std::move(v));
  }

  const ShadowRelight r = relight_target_shadow(model, target, target, nullptr, views, raster, {});
  ASSERT_TRUE(r.fit.found) << r.fit.reason;
  double both_err = 0, both_photo = 0, alone_err = 0, alone_photo = 0;
  std::size_t n_both = 0, n_alone = 0;
  for (std::size_t k = 0; k < views.size(); ++k)
    for (std::size_t p = 0; p < 64 * 64; ++p) {
      if (!both[k][p] && !target_only[k][p]) continue;
      // Against the truth: the relit photo, and what it is measured by - the lit floor where both shade it
      // (a relight by the target alone), the photo where the target alone does.
      double err = 0, photo = 0;
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = std::size_t(c) * 64 * 64 + p;
        err += std::abs(views[k].image[i] - truth[k][i]);
        photo += std::abs((both[k][p] ? lit[k][i] : shaded[k][i]) - truth[k][i]);
      }
      if (both[k][p]) ++n_both, both_err += err, both_photo += photo;
      else ++n_alone, alone_err += err, alone_photo += photo;
    }
  ASSERT_GT(n_both, 20u);
  ASSERT_GT(n_alone, 20u);
  // Relit like the target alone, the doubly shaded floor would come out as bright as the lit floor.
  EXPECT_LT(both_err, 0.35 * both_photo) << n_both << " pixels in both shadows; " << r.fit.reason;
  EXPECT_LT(alone_err, 0.5 * alone_photo) << n_alone << " pixels in the target's shadow alone; " << r.fit.reason;
}

}  // namespace
}  // namespace goris
