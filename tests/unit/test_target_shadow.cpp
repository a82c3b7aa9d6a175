// The target's cast shadow (removal/shadow/target_shadow.h): a textured floor z = 0 shaded by a ball-shaped
// target under a tilted light, with an analytic occluder (ray-sphere); the light's direction and strength
// come back and relighting restores the unshaded floor. Without a shadow in the colours nothing is found;
// bad input is an error. The Gaussian-scene glue (tracing the target's Gaussians) is checked as well.
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


struct Floor {
  std::vector<glm::vec3> centres, colours, lit;  // lit: the colour without the target's shadow
  std::vector<float> weights;
  SelectionMask target, candidates;
  std::vector<bool> shaded;
};

// A 60 x 60 floor over [-2, 2]^2 with a texture, the ball's centres (target), a few centres of another
// object above the floor. shadow = false renders the floor unshaded; strength: the share of the light the
// ball takes away, per channel; light: the light's direction; grain: the amplitude of a random texture
// (a marble's veins, a reflection baked into the colour) added to the smooth one.
Floor make_floor(bool shadow, const glm::dvec3& strength = kStrength, const glm::dvec3& light = kLight,
                 float grain = 0.0f) {
  Floor f;
  const double gamma = 2.2;
  std::mt19937 grain_rng(11);
  std::uniform_real_distribution<float> g(-grain, grain);
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 60; ++x) {
      const glm::vec3 p(-2.0f + 4.0f * (x + 0.5f) / 60, -2.0f + 4.0f * (y + 0.5f) / 60, 0.0f);
      const float r = grain > 0.0f ? g(grain_rng) : 0.0f;
      const glm::vec3 base(0.6f + 0.1f * std::sin(17.0f * p.x) * std::cos(13.0f * p.y) + r, 0.55f + r,
                           0.5f + 0.05f * std::sin(19.0f * p.y) + r);
      const bool in = hits_ball(p, glm::vec3(light));
      glm::vec3 c = base;
      if (shadow && in)
        for (int k = 0; k < 3; ++k) c[k] = float(std::pow(std::pow(double(base[k]), gamma) * (1.0 - strength[k]), 1.0 / gamma));
      f.centres.push_back(p);
      f.colours.push_back(c);
      f.lit.push_back(base);
      f.weights.push_back(0.9f);
      f.target.push_back(0);
      f.shaded.push_back(in);
    }
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  for (int i = 0; i < 300; ++i) {
    f.centres.push_back(kBall + kBallRadius * in_unit_ball(rng));
    f.colours.push_back({0.8f, 0.2f, 0.2f});
    f.lit.push_back({0.8f, 0.2f, 0.2f});
    f.weights.push_back(0.9f);
    f.target.push_back(1);
    f.shaded.push_back(false);
  }
  for (int i = 0; i < 80; ++i) {  // another object: near the target but not on the floor
    f.centres.push_back({0.7f + 0.1f * u(rng), 0.7f + 0.1f * u(rng), 0.3f + 0.2f * u(rng)});
    f.colours.push_back({0.1f, 0.1f, 0.1f});
    f.lit.push_back({0.1f, 0.1f, 0.1f});
    f.weights.push_back(0.9f);
    f.target.push_back(0);
    f.shaded.push_back(false);
  }
  f.candidates.assign(f.centres.size(), 1);
  return f;
}

const TargetOcclusion kBallOcclusion = [](const std::vector<glm::vec3>& o, const std::vector<glm::vec3>& d,
                                          std::vector<float>& alpha) {
  for (std::size_t i = 0; i < o.size(); ++i) alpha[i] = hits_ball(o[i], d[i]) ? 1.0f : 0.0f;
};

// The floor's Gaussians as the samples (the pipeline takes pixels; the method does not care).
struct Fitted {
  ShadowGeometry geo;
  ShadowSamples samples;
  std::vector<std::size_t> index;  // sample -> Gaussian
  TargetShadow fit;
};
Fitted fit_floor(const Floor& f, const glm::dvec3* known_light = nullptr) {
  Fitted r;
  r.geo = shadow_geometry(f.centres, f.weights, f.target, f.candidates);
  for (std::size_t i = 0; i < f.centres.size(); ++i)
    if (!f.target[i] && r.geo.found && r.geo.near_plane(f.centres[i]) && r.geo.in_reach(f.centres[i]))
      r.samples.add(f.centres[i], f.colours[i], f.weights[i]), r.index.push_back(i);
  r.fit = fit_target_shadow(r.geo, r.samples, kBallOcclusion, {}, known_light);
  return r;
}

double degrees_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
}

// A light nearly overhead puts most of the ball's shadow under the ball, where no view sees the floor; the
// thin crescent that shows is small beside a grainy texture, and the search over the whole sky finds no
// shadow. Told where the environment's light is (within the cap), the fit finds it near there.
TEST(TargetShadow, LightOverheadFoundNearTheKnownLight) {
  const glm::dvec3 overhead = glm::normalize(glm::dvec3(0.25, 0.1, 1.0));
  const Floor f = make_floor(true, kStrength, overhead, 0.25f);
  const Fitted blind = fit_floor(f);
  ASSERT_TRUE(blind.geo.found) << blind.geo.reason;
  EXPECT_FALSE(blind.fit.found) << blind.fit.reason;
  // The environment's brightest region 17 degrees off the true light.
  const glm::dvec3 known = glm::normalize(glm::dvec3(-0.05, 0.1, 1.0));
  ASSERT_NEAR(degrees_between(known, overhead), 17.0, 1.0);
  const Fitted told = fit_floor(f, &known);
  ASSERT_TRUE(told.fit.found) << told.fit.reason;
  EXPECT_TRUE(told.fit.from_known_light);
  EXPECT_NE(told.fit.reason.find("near the environment's"), std::string::npos) << told.fit.reason;
  EXPECT_LT(degrees_between(told.fit.light_direction, overhead), 8.0) << told.fit.reason;
  EXPECT_NEAR(told.fit.strength_luminance, 0.57, 0.2) << told.fit.reason;
  // Relighting takes the crescent back toward the unshaded floor.
  const std::vector<float> frac = shadow_fraction(told.fit, told.samples.position, kBallOcclusion);
  double before = 0, after = 0;
  int shaded = 0;
  for (std::size_t k = 0; k < told.index.size(); ++k) {
    const std::size_t i = told.index[k];
    if (!f.shaded[i] || told.geo.in_reach(f.centres[i]) == false) continue;
    before += glm::length(f.colours[i] - f.lit[i]);
    after += glm::length(f.colours[i] * shadow_gain(told.fit, frac[k]) - f.lit[i]);
    ++shaded;
  }
  ASSERT_GT(shaded, 10);
  EXPECT_LT(after, 0.5 * before) << "colour error in the shadow over " << shaded << " samples";
}

// The known light changes nothing where the search finds the shadow by itself, and finds nothing where the
// colours hold no shadow.
TEST(TargetShadow, KnownLightOnlyWhereTheSearchFindsNone) {
  const glm::dvec3 known = glm::normalize(glm::dvec3(0.0, 0.0, 1.0));
  const Fitted plain = fit_floor(make_floor(true));
  const Fitted told = fit_floor(make_floor(true), &known);
  ASSERT_TRUE(plain.fit.found && told.fit.found) << plain.fit.reason << " / " << told.fit.reason;
  EXPECT_FALSE(told.fit.from_known_light);
  EXPECT_EQ(told.fit.light_direction, plain.fit.light_direction);
  EXPECT_EQ(told.fit.strength, plain.fit.strength);
  const Fitted none = fit_floor(make_floor(false, kStrength, kLight, 0.25f), &known);
  EXPECT_FALSE(none.fit.found) << none.fit.reason;
  EXPECT_NE(none.fit.reason.find("near the environment's light"), std::string::npos) << none.fit.reason;
}

TEST(TargetShadow, FindsTheLightAndRelightsTheFloor) {
  const Floor f = make_floor(true);
  const Fitted r = fit_floor(f);
  ASSERT_TRUE(r.geo.found) << r.geo.reason;
  EXPECT_NEAR(std::abs(r.geo.plane.normal.z), 1.0, 1e-3);
  EXPECT_GT(r.geo.up.z, 0.99);
  ASSERT_TRUE(r.fit.found) << r.fit.reason;
  const TargetShadow& s = r.fit;
  const double angle = std::acos(std::clamp(glm::dot(s.light_direction, kLight), -1.0, 1.0)) * 180.0 / 3.14159265;
  EXPECT_LT(angle, 4.0) << s.reason;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.strength[c], kStrength[c], 0.08) << "channel " << c << ": " << s.reason;
  EXPECT_GT(s.r2, 0.5);
  // Relit colours are the unshaded floor again; the lit floor is (nearly all) untouched.
  const std::vector<float> frac = shadow_fraction(s, r.samples.position, kBallOcclusion);
  double before = 0, after = 0;
  int shaded = 0, lit = 0, wrongly_relit = 0;
  for (std::size_t k = 0; k < r.index.size(); ++k) {
    const std::size_t i = r.index[k];
    const glm::vec3 relit = f.colours[i] * shadow_gain(s, frac[k]);
    if (f.shaded[i]) {
      before += glm::length(f.colours[i] - f.lit[i]);
      after += glm::length(relit - f.lit[i]);
      ++shaded;
    } else {
      ++lit;
      wrongly_relit += glm::length(relit - f.lit[i]) > 0.06f ? 1 : 0;  // the shadow's edge may be off by a sample
    }
  }
  ASSERT_GT(shaded, 20);
  EXPECT_LT(wrongly_relit, lit / 100) << "of " << lit << " unshaded samples";
  EXPECT_LT(after / shaded, 0.3 * before / shaded) << "mean colour error in the shadow, before " << before / shaded;
}

// An area light with little ambient light leaves a nearly black shadow (the suite's clearest shadows measure
// k = 0.9 and more): its strength comes back, and relighting brings the floor back instead of leaving it dim.
TEST(TargetShadow, DeepShadowRelitInFull) {
  const glm::dvec3 deep(0.95, 0.94, 0.93);
  const Floor f = make_floor(true, deep);
  const Fitted r = fit_floor(f);
  ASSERT_TRUE(r.fit.found) << r.fit.reason;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.fit.strength[c], deep[c], 0.02) << "channel " << c << ": " << r.fit.reason;
  const std::vector<float> frac = shadow_fraction(r.fit, r.samples.position, kBallOcclusion);
  double before = 0, after = 0;
  int shaded = 0;
  for (std::size_t k = 0; k < r.index.size(); ++k) {
    const std::size_t i = r.index[k];
    if (!f.shaded[i] || frac[k] < 0.99f) continue;  // the shadow's core
    before += glm::length(f.colours[i] - f.lit[i]);
    after += glm::length(f.colours[i] * shadow_gain(r.fit, frac[k]) - f.lit[i]);
    ++shaded;
  }
  ASSERT_GT(shaded, 10);
  EXPECT_LT(after / shaded, 0.2 * before / shaded) << "mean colour error in the shadow's core, before " << before / shaded;
}

// Over a mirror the learned mirror world is a plane of its own below the surface, and can be denser than
// the surface near the target: the support plane is the one the target rests on.
TEST(TargetShadow, SupportPlaneIsTheOneTheTargetRestsOn) {
  Floor f = make_floor(true);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-0.45f, 0.45f);
  for (int i = 0; i < 2000; ++i) {
    f.centres.push_back({u(rng), u(rng), -0.5f});
    f.colours.push_back(glm::vec3(0.3f));
    f.weights.push_back(0.9f);
    f.target.push_back(0);
    f.candidates.push_back(1);
  }
  const ShadowGeometry geo = shadow_geometry(f.centres, f.weights, f.target, f.candidates);
  ASSERT_TRUE(geo.found) << geo.reason;
  EXPECT_NEAR(geo.plane.signed_distance(glm::dvec3(0.0)), 0.0, geo.plane.tolerance);
  EXPECT_GT(std::abs(geo.plane.signed_distance(glm::dvec3(0.0, 0.0, -0.5))), 0.4);
}

TEST(TargetShadow, NoShadowInTheColoursFindsNone) {
  const Fitted r = fit_floor(make_floor(false));
  ASSERT_TRUE(r.geo.found);
  EXPECT_FALSE(r.fit.found) << r.fit.reason;
  EXPECT_EQ(shadow_gain(r.fit, 1.0f), glm::vec3(1.0f));
  for (float v : shadow_fraction(r.fit, r.samples.position, kBallOcclusion)) ASSERT_EQ(v, 0.0f);
}

// Step 6: the light found must cast the other objects' shadows as well. A neighbour (a second ball beside the
// target) darkens the floor under the true light: at the true light its shadow is where the photos are dark;
// at a wrong light its shadow falls on lit floor, and the check says so. Without a neighbour's shadow among the
// samples it says nothing.
TEST(TargetShadow, TheLightMustCastTheOtherObjectsShadowsToo) {
  const glm::vec3 neighbour(0.5f, 0.4f, 0.25f);
  constexpr float kNeighbourRadius = 0.2f;
  auto hits_neighbour = [&](const glm::vec3& o, const glm::vec3& d) {
    const glm::vec3 oc = o - neighbour;
    const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - kNeighbourRadius * kNeighbourRadius;
    return b * b - c > 0 && -b + std::sqrt(b * b - c) > 0;
  };
  const TargetOcclusion neighbour_occlusion = [&](const std::vector<glm::vec3>& o, const std::vector<glm::vec3>& d,
                                                  std::vector<float>& alpha) {
    for (std::size_t i = 0; i < o.size(); ++i) alpha[i] = hits_neighbour(o[i], d[i]) ? 1.0f : 0.0f;
  };
  const TargetOcclusion nothing = [](const std::vector<glm::vec3>&, const std::vector<glm::vec3>&,
                                     std::vector<float>& alpha) { std::fill(alpha.begin(), alpha.end(), 0.0f); };
  Floor f = make_floor(true);
  for (std::size_t i = 0; i < f.centres.size(); ++i)  // the neighbour's shadow under the same light, as deep
    if (!f.target[i] && std::abs(f.centres[i].z) < 1e-6f && hits_neighbour(f.centres[i], glm::vec3(kLight)))
      for (int c = 0; c < 3; ++c)
        f.colours[i][c] = float(std::pow(std::pow(double(f.lit[i][c]), 2.2) * (1.0 - kStrength[c]), 1.0 / 2.2));
  const Fitted r = fit_floor(f);
  ASSERT_TRUE(r.fit.found) << r.fit.reason;
  const OthersShadow at_true = others_shadow(r.fit, r.samples, kBallOcclusion, neighbour_occlusion);
  EXPECT_GT(at_true.shaded_share, 0.02) << "the neighbour's shadow lies among the samples";
  EXPECT_NEAR(at_true.strength, 0.55, 0.15);
  EXPECT_FALSE(at_true.contradicts);

  TargetShadow wrong = r.fit;  // a lower light from across the sky: the neighbour's shadow on lit floor
  wrong.light_direction = glm::normalize(glm::dvec3(-kLight.x, -kLight.y, 0.5 * kLight.z));
  const OthersShadow at_wrong = others_shadow(wrong, r.samples, kBallOcclusion, neighbour_occlusion);
  EXPECT_GT(at_wrong.shaded_share, 0.02);
  EXPECT_LT(at_wrong.strength, 0.15);
  EXPECT_TRUE(at_wrong.contradicts);

  const OthersShadow alone = others_shadow(wrong, r.samples, kBallOcclusion, nothing);
  EXPECT_EQ(alone.shaded_share, 0.0);
  EXPECT_FALSE(alone.contradicts) << "no neighbour, no evidence against the light";
}

TEST(TargetShadow, NoSupportPlaneNoShadow) {
  Floor f = make_floor(true);
  std::fill(f.candidates.begin(), f.candidates.end(), 0);  // nothing may carry the shadow
  const ShadowGeometry geo = shadow_geometry(f.centres, f.weights, f.target, f.candidates);
  EXPECT_FALSE(geo.found);
  ShadowSamples samples;
  for (std::size_t i = 0; i < 100; ++i) samples.add(f.centres[i], f.colours[i]);
  const TargetShadow s = fit_target_shadow(geo, samples, kBallOcclusion);
  EXPECT_FALSE(s.found);
  EXPECT_EQ(s.reason, geo.reason);
  EXPECT_NE(s.reason.find("Gaussians near the target"), std::string::npos) << s.reason;

  // A plane from elsewhere (the glossy surface's) serves when it passes within reach of the target ...
  MirrorPlane floor;
  floor.found = true;
  floor.normal = {0.0, 0.0, -1.0};
  floor.tolerance = 0.01;
  const ShadowGeometry with_floor = shadow_geometry(f.centres, f.weights, f.target, f.candidates, {}, &floor);
  ASSERT_TRUE(with_floor.found);
  EXPECT_GT(with_floor.up.z, 0.99);  // toward the target, whatever the plane's own orientation
  const Fitted r = fit_floor(make_floor(true));
  EXPECT_TRUE(fit_target_shadow(with_floor, r.samples, kBallOcclusion).found);
  // ... and not when it lies far from it.
  MirrorPlane far = floor;
  far.offset = 10.0;
  EXPECT_FALSE(shadow_geometry(f.centres, f.weights, f.target, f.candidates, {}, &far).found);
}

TEST(TargetShadow, BadInputIsAnError) {
  Floor f = make_floor(true);
  std::vector<float> short_weights(f.weights.begin(), f.weights.end() - 1);
  test::expect_error([&] { shadow_geometry(f.centres, short_weights, f.target, f.candidates); }, "differ in size");
  const SelectionMask none(f.centres.size(), 0);
  test::expect_error([&] { shadow_geometry(f.centres, f.weights, none, f.candidates); }, "target is empty");
  const Fitted r = fit_floor(f);
  ShadowSamples broken = r.samples;
  broken.weight.pop_back();
  test::expect_error([&] { fit_target_shadow(r.geo, broken, kBallOcclusion); }, "differ in size");
}

// A Gaussian model of the ball: the tracer over its Gaussians stands in for the analytic occluder; a camera
// above the floor finds the floor's pixels; relighting a photo of the shaded floor gives the lit one.
TEST(TargetShadow, GaussianOccluderPlanePixelsAndRelitPhoto) {
  const Floor f = make_floor(true);
  const std::size_t n = f.centres.size();
  std::vector<test::TestGaussian> gs(n);
  for (std::size_t i = 0; i < n; ++i) gs[i] = {f.centres[i], f.target[i] ? 0.06f : 0.03f, 0.95f, f.colours[i], 0.5f};
  const GaussianModel model = test::make_model(gs);
  const TargetOccluder occ(model, f.target);
  // The floor shaded by the Gaussian ball itself (its shadow is softer and wider than the analytic one's).
  auto shaded = [&](const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& base) {
    std::vector<float> a(points.size());
    occ.function()(points, std::vector<glm::vec3>(points.size(), glm::vec3(kLight)), a);
    std::vector<glm::vec3> out(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
      for (int c = 0; c < 3; ++c)
        out[k][c] = float(std::pow(std::pow(double(base[k][c]), 2.2) * (1.0 - kStrength[c] * a[k]), 1.0 / 2.2));
    return out;
  };
  Fitted r = fit_floor(f);
  std::vector<glm::vec3> floor_lit;
  for (std::size_t i : r.index) floor_lit.push_back(f.lit[i]);
  r.samples.colour = shaded(r.samples.position, floor_lit);
  r.fit = fit_target_shadow(r.geo, r.samples, occ.function());
  ASSERT_TRUE(r.fit.found) << r.fit.reason;
  EXPECT_LT(std::acos(std::clamp(glm::dot(r.fit.light_direction, kLight), -1.0, 1.0)) * 180.0 / 3.14159265, 4.0)
      << r.fit.reason;
  EXPECT_NEAR(r.fit.strength_luminance, 0.55, 0.08) << r.fit.reason;

  // A camera 3 units above the floor looking down (OpenCV axes: x right, y down, z forward).
  Camera cam;
  cam.width = cam.height = 64;
  cam.fx = cam.fy = 40.0f;
  cam.cx = cam.cy = 32.0f;
  cam.R = glm::mat3(glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1));  // columns: world axes in camera
  cam.t = -(cam.R * glm::vec3(0, 0, 3));
  const std::size_t hw = 64 * 64;
  std::vector<float> depth(hw), alpha(hw, 1.0f);
  for (std::size_t p = 0; p < hw; ++p) depth[p] = 3.0f;  // the floor, seen straight down
  depth[0] = 2.0f;                                        // something in front of the floor: not a plane pixel
  alpha[1] = 0.0f;                                        // nothing there
  const PlanePixels px = support_plane_pixels(cam, depth, alpha, r.geo);
  ASSERT_GT(px.size(), 100u);
  for (std::size_t k = 0; k < px.size(); ++k) {
    ASSERT_NE(px.pixel[k], 0u);
    ASSERT_NE(px.pixel[k], 1u);
    ASSERT_NEAR(px.point[k].z, 0.0f, 1e-3f);
    ASSERT_TRUE(r.geo.in_reach(px.point[k]));
  }
  // The photo: the analytic shaded floor at each plane pixel; relit, it is the unshaded colour.
  std::vector<float> photo(3 * hw, 0.0f), lit(3 * hw, 0.0f);
  const std::vector<glm::vec3> seen = shaded(px.point, std::vector<glm::vec3>(px.size(), glm::vec3(0.6f)));
  for (std::size_t k = 0; k < px.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      lit[std::size_t(c) * hw + px.pixel[k]] = 0.6f;
      photo[std::size_t(c) * hw + px.pixel[k]] = seen[k][c];
    }
  const std::vector<float> s = shadow_fraction(r.fit, px.point, occ.function());
  double before = 0, after = 0;
  std::vector<float> relit = photo;
  relight_planar(relit, hw, px, s, r.fit);
  for (std::size_t i = 0; i < 3 * hw; ++i) before += std::abs(photo[i] - lit[i]), after += std::abs(relit[i] - lit[i]);
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.3 * before) << r.fit.reason << ", " << px.size() << " plane pixels";
  Image im(64, 64, 3);
  for (std::size_t p = 0; p < hw; ++p)
    for (int c = 0; c < 3; ++c) im.pixels[p * 3 + std::size_t(c)] = photo[std::size_t(c) * hw + p];
  relight_image(im, px, s, r.fit);
  for (std::size_t p = 0; p < hw; ++p)
    for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(im.pixels[p * 3 + std::size_t(c)], relit[std::size_t(c) * hw + p]);
  test::expect_error([&] { relight_planar(relit, hw, px, std::vector<float>(3), r.fit); }, "3 shadow values");
  test::expect_error([&] { support_plane_pixels(cam, std::vector<float>(5), alpha, r.geo); }, "64x64");
}

}  // namespace
}  // namespace goris
