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
#include "tests/unit/test_selection_scene.h"

namespace goris {
namespace {

const glm::vec3 kBall(0.0f, 0.0f, 0.5f);
constexpr float kBallRadius = 0.3f;
const glm::dvec3 kLight = glm::normalize(glm::dvec3(0.5, -0.3, 1.0));
const glm::dvec3 kStrength(0.6, 0.55, 0.45);

bool hits_ball(const glm::vec3& o, const glm::vec3& d) {
  const glm::vec3 oc = o - kBall;
  const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - kBallRadius * kBallRadius;
  const float disc = b * b - c;
  return disc > 0 && -b + std::sqrt(disc) > 0;
}

// A uniform random point in the unit ball (rejection sampling).
glm::vec3 in_unit_ball(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1);
  glm::vec3 d;
  do d = {u(rng), u(rng), u(rng)};
  while (glm::length(d) > 1.0f);
  return d;
}

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

namespace goris {
namespace {

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
  const ShadowGeometry floor = floor_plane();
  const RasterSettings raster;
  std::vector<TrainView> views;
  std::vector<std::vector<float>> lit;
  std::vector<std::vector<std::uint8_t>> in_shadow;
  for (int k = 0; k < 8; ++k) {
    TrainView v = ring_view(k);
    const RasterOutput r = rasterize(model.view(false), v.camera, raster, Device::CPU);
    v.image = r.gbuffer.color.to_host();
    lit.push_back(v.image);
    const PlanePixels px = support_plane_pixels(v.camera, r.gbuffer.median_depth.to_host(), r.gbuffer.alpha.to_host(), floor);
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

  const ShadowGeometry floor = floor_plane();
  const RasterSettings raster;
  std::vector<TrainView> views;
  std::vector<std::vector<float>> lit, truth, shaded;  // shaded: the photos
  std::vector<std::vector<std::uint8_t>> both, target_only;
  for (int k = 0; k < 8; ++k) {
    TrainView v = ring_view(k);
    const RasterOutput r = rasterize(model.view(false), v.camera, raster, Device::CPU);
    v.image = r.gbuffer.color.to_host();
    lit.push_back(v.image);
    const PlanePixels px = support_plane_pixels(v.camera, r.gbuffer.median_depth.to_host(), r.gbuffer.alpha.to_host(), floor);
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
