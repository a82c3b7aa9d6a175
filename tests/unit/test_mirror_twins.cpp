// The target's mirror twin below a planar glossy surface (core/scene/mirror_twins.h): a table top of
// glossy centres, a target sphere above it and its learned mirror copy below, another object with its own
// twin that must stay, noise; the same scene tilted; surfaces that are no plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_selection_scene.h"

namespace goris {
namespace {

enum Kind : std::uint8_t { Table, Target, TargetTwin, Other, OtherTwin, Floater };

struct Scene {
  std::vector<glm::vec3> centres;
  std::vector<Kind> kind;
  std::vector<std::uint8_t> glossy;
  SelectionMask target;
  void add(glm::vec3 p, Kind k, bool is_glossy) {
    centres.push_back(p);
    kind.push_back(k);
    glossy.push_back(is_glossy);
    target.push_back(k == Target);
  }
};

// Table z = 0 over [-1, 1]^2; target sphere (radius 0.2) at (0, 0, 0.3); its twin at (0, 0, -0.3) with
// jittered centres (learned, not exact); another sphere at (0.6, 0.6, 0.25) and its twin; the twins are
// glossy (they are seen through the glossy surface), the objects are not.
Scene table_scene(const glm::mat4& pose) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  std::normal_distribution<float> jitter(0.0f, 0.01f);
  Scene s;
  auto put = [&](glm::vec3 p, Kind k, bool g) { s.add(glm::vec3(pose * glm::vec4(p, 1.0f)), k, g); };
  for (int i = 0; i < 600; ++i) put({u(rng), u(rng), 0.003f * u(rng)}, Table, true);
  auto ball = [&](glm::vec3 c, float r) {
    glm::vec3 d;
    do d = {u(rng), u(rng), u(rng)};
    while (glm::length(d) > 1.0f);
    return c + r * d;
  };
  for (int i = 0; i < 150; ++i) {
    const glm::vec3 p = ball({0, 0, 0.3f}, 0.2f);
    put(p, Target, false);
    put(glm::vec3(p.x, p.y, -p.z) + glm::vec3(jitter(rng), jitter(rng), jitter(rng)), TargetTwin, true);
  }
  for (int i = 0; i < 80; ++i) {
    const glm::vec3 p = ball({0.6f, 0.6f, 0.25f}, 0.15f);
    put(p, Other, false);
    put(glm::vec3(p.x, p.y, -p.z), OtherTwin, true);
  }
  for (int i = 0; i < 30; ++i) put({u(rng), u(rng), -0.8f + 0.1f * u(rng)}, Floater, true);
  return s;
}

void expect_twins_found(const Scene& s, const MirrorTwins& t, glm::dvec3 normal) {
  ASSERT_TRUE(t.plane.found);
  EXPECT_NEAR(std::abs(glm::dot(t.plane.normal, normal)), 1.0, 1e-3);
  EXPECT_GT(glm::dot(t.plane.normal, normal), 0.0) << "the normal points to the target's side";
  std::size_t twins = 0, wrong = 0;
  for (std::size_t i = 0; i < s.centres.size(); ++i) {
    if (s.kind[i] == TargetTwin) twins += t.twins[i];
    else wrong += t.twins[i];
  }
  EXPECT_GE(twins, 145u) << "of 150 twin centres";
  EXPECT_EQ(wrong, 0u) << "the table, the target itself, the other object's twin and floaters stay";
  EXPECT_EQ(t.count, twins + wrong);
}

TEST(MirrorTwins, SelectsTheTargetsTwinBelowTheTableAndNothingElse) {
  const Scene s = table_scene(glm::mat4(1.0f));
  const MirrorTwins t = select_mirror_twins(s.centres, s.glossy, s.target);
  expect_twins_found(s, t, {0, 0, 1});
  EXPECT_NEAR(t.plane.offset, 0.0, 0.01);
  EXPECT_GE(t.plane.inliers, 600u);
}

TEST(MirrorTwins, TiltedAndShiftedSceneGivesTheSameAnswer) {
  glm::mat4 pose = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -2.0f, 5.0f));
  pose = glm::rotate(pose, 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  const Scene s = table_scene(pose);
  const MirrorTwins t = select_mirror_twins(s.centres, s.glossy, s.target);
  expect_twins_found(s, t, glm::dvec3(glm::mat3(pose) * glm::vec3(0, 0, 1)));
}

TEST(MirrorTwins, AFewGaussiansInTheMirroredHullAreNoTwin) {
  // A dim reflector: no mirror world, only a tenth of the twin's Gaussians below the table (the surface's
  // underside, noise). Nothing is selected; with the share rule off, they would be.
  Scene s = table_scene(glm::mat4(1.0f));
  Scene sparse;
  int kept = 0;
  for (std::size_t i = 0; i < s.centres.size(); ++i)
    if (s.kind[i] != TargetTwin || kept++ % 10 == 0) sparse.add(s.centres[i], s.kind[i], s.glossy[i]);
  const MirrorTwins t = select_mirror_twins(sparse.centres, sparse.glossy, sparse.target);
  EXPECT_TRUE(t.plane.found);
  EXPECT_EQ(t.count, 0u);
  EXPECT_EQ(std::count(t.twins.begin(), t.twins.end(), 1), 0);
  EXPECT_GE(t.candidates, 10u);
  EXPECT_EQ(t.target_above, 150u);
  MirrorSettings no_rule;
  no_rule.min_twin_share = 0;
  EXPECT_EQ(select_mirror_twins(sparse.centres, sparse.glossy, sparse.target, no_rule).count, t.candidates);
}

TEST(MirrorTwins, NoPlaneNoTwins) {
  // Glossy centres scattered through a box lie on no plane: nothing is selected.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<glm::vec3> c;
  std::vector<std::uint8_t> glossy;
  SelectionMask target;
  for (int i = 0; i < 500; ++i) c.push_back({u(rng), u(rng), u(rng)}), glossy.push_back(i >= 50), target.push_back(i < 50);
  const MirrorTwins t = select_mirror_twins(c, glossy, target);
  EXPECT_FALSE(t.plane.found);
  EXPECT_EQ(t.count, 0u);
  // Too few glossy centres to call anything a plane.
  std::vector<std::uint8_t> few(c.size(), 0);
  for (int i = 50; i < 60; ++i) few[std::size_t(i)] = 1;
  EXPECT_FALSE(select_mirror_twins(c, few, target).plane.found);
  test::expect_error([&] { select_mirror_twins(c, glossy, SelectionMask(3, 0)); }, "selection entries");
}

TEST(SelectionPoints, FlatNormalIsTheRotatedSmallestAxisOfFlatGaussiansOnly) {
  GaussianModel m = test::make_model(std::vector<test::TestGaussian>(4));
  float* ls = m.values(Param::LogScale);
  float* rot = m.values(Param::Rotation);
  auto set_scales = [&](int i, float a, float b, float c) {
    ls[3 * i] = std::log(a), ls[3 * i + 1] = std::log(b), ls[3 * i + 2] = std::log(c);
  };
  set_scales(0, 0.1f, 0.2f, 0.01f);   // flat, smallest axis z, no rotation
  set_scales(1, 0.01f, 0.1f, 0.1f);   // flat, smallest axis x, turned 90 degrees about z: world y
  const float h = std::sqrt(0.5f);
  rot[4] = 2.0f * h, rot[5] = 0.0f, rot[6] = 0.0f, rot[7] = 2.0f * h;  // unnormalised (w, x, y, z)
  set_scales(2, 0.05f, 0.06f, 0.04f);  // round: no normal
  set_scales(3, 0.1f, 0.1f, 0.031f);   // smallest just over 0.3 x middle: not flat
  const std::vector<glm::vec3> flat_normal = flat_normals(m);
  ASSERT_EQ(flat_normal.size(), 4u);
  EXPECT_NEAR(std::abs(flat_normal[0].z), 1.0f, 1e-6f);
  EXPECT_NEAR(std::abs(flat_normal[1].y), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(flat_normal[1]), 1.0f, 1e-6f);
  EXPECT_EQ(flat_normal[2], glm::vec3(0.0f));
  EXPECT_EQ(flat_normal[3], glm::vec3(0.0f));
}

TEST(MirrorTwins, SurfaceNormalsPickTheTableOverATiltedPlaneThroughMoreCentres) {
  // What the grey start gave on steel_snowman: nearly every Gaussian glossy, the table top a thin layer,
  // and a tilted plane through the table's edge and the objects holding more centres within the tolerance
  // than the table. With the Gaussians' flat normals (table: up; objects: scattered) the table wins.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<glm::vec3> c, normals;
  const glm::vec3 tilt = glm::normalize(glm::vec3(0.2f, 0.0f, 1.0f));
  for (int i = 0; i < 300; ++i) c.push_back({u(rng), u(rng), 0.002f * u(rng)}), normals.push_back({0, 0, 1});
  for (int i = 0; i < 700; ++i) {  // a dense slab along z = -0.2 x + 0.3, with surface normals all over
    const float x = u(rng), y = u(rng);
    c.push_back(glm::vec3(x, y, -0.2f * x + 0.3f) + 0.002f * u(rng) * tilt);
    normals.push_back(glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.01f)));
  }
  std::vector<std::uint8_t> glossy(c.size(), 1);
  const SelectionMask target(c.size(), 0);
  const MirrorPlane by_distance = fit_mirror_plane(c);
  ASSERT_TRUE(by_distance.found);
  EXPECT_GT(std::abs(glm::dot(by_distance.normal, glm::dvec3(tilt))), 0.999) << "distance alone takes the slab";
  const MirrorPlane with_normals = fit_mirror_plane(c, {}, normals);
  ASSERT_TRUE(with_normals.found);
  EXPECT_GT(std::abs(with_normals.normal.z), 0.9999);
  EXPECT_NEAR(std::abs(with_normals.offset), 0.0, 0.005);
  EXPECT_EQ(with_normals.inliers, 300u) << "only the table's centres agree in position and normal";
  EXPECT_EQ(select_mirror_twins(c, glossy, target, {}, normals).plane.inliers, 300u);
  // A zero normal (a round Gaussian) is never an inlier.
  std::vector<glm::vec3> round(c.size(), glm::vec3(0.0f));
  EXPECT_FALSE(fit_mirror_plane(c, {}, round).found);
  test::expect_error([&] { fit_mirror_plane(c, {}, std::vector<glm::vec3>(3)); }, "normals");
  test::expect_error([&] { select_mirror_twins(c, glossy, target, {}, std::vector<glm::vec3>(3)); }, "3 normals");
}

TEST(MirrorTwins, WithNormalsTheInlierShareCountsFlatGaussiansOnly) {
  // Steel_snowman without the warm-up material losses (8K, seed 0): 1,056 flat table Gaussians of 12,754
  // glossy ones (8 %, under the 10 % a plane needs) but of ~7,200 flat ones. Here: a table of 80 flat
  // centres among 1,000 glossy ones, of which 400 are flat; the other 920 are round (zero normal).
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<glm::vec3> c, normals;
  for (int i = 0; i < 80; ++i) c.push_back({u(rng), u(rng), 0.002f * u(rng)}), normals.push_back({0, 0, 1});
  for (int i = 0; i < 320; ++i)  // flat but scattered in position and orientation
    c.push_back({u(rng), u(rng), u(rng)}), normals.push_back(glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + 0.01f));
  for (int i = 0; i < 600; ++i) c.push_back({u(rng), u(rng), u(rng)}), normals.push_back(glm::vec3(0.0f));
  const MirrorPlane p = fit_mirror_plane(c, {}, normals);
  EXPECT_EQ(p.candidates, 400u);
  EXPECT_GE(p.inliers, 80u);
  EXPECT_LT(p.inliers, 100u);  // 80 / 1,000 glossy would fail the 10 %; 80+ / 400 flat passes
  EXPECT_TRUE(p.found);
  EXPECT_GT(std::abs(p.normal.z), 0.999);
  // Fewer flat table centres than 10 % of the flat ones: no plane.
  MirrorSettings strict;
  strict.min_inlier_fraction = 0.3;
  EXPECT_FALSE(fit_mirror_plane(c, strict, normals).found);
}

}  // namespace
}  // namespace goris
