// The target's reflection in a planar glossy surface from geometry alone: glossy Gaussians from the photos'
// masks, the target mirrored through the plane (centres and covariances), and its coverage on the glossy
// surface as the reflection mask.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "render/raster/raster_types.h"
#include "core/util/error.h"
#include "render/removal/planar_reflection.h"
#include "tests/unit/test_selection_scene.h"

using namespace goris;
using goris::test::look_at;
using goris::test::make_model;
using goris::test::TestGaussian;

namespace {
MirrorPlane floor_plane() {  // z = 0, the target's side up
  MirrorPlane p;
  p.found = true;
  p.normal = {0, 0, 1};
  p.offset = 0;
  return p;
}

glm::mat3 covariance(const float* log_scale, const float* q) {
  const glm::quat r = glm::normalize(glm::quat(q[0], q[1], q[2], q[3]));
  const glm::mat3 R = glm::mat3_cast(r);
  glm::mat3 S(0.0f);
  for (int k = 0; k < 3; ++k) S[k][k] = std::exp(2.0f * log_scale[k]);
  return R * S * glm::transpose(R);
}
}  // namespace

TEST(PlanarReflection, GlossyGaussiansAreThoseInsideTheMasksOfMostViews) {
  // Two cameras above the floor; the mask marks the image's left half (the world side x < 0 for both).
  const std::vector<Camera> cams = {look_at({0, -4, 3}, {0, 0, 0}), look_at({0.5f, -4, 3}, {0, 0, 0})};
  std::vector<std::vector<float>> masks(2, std::vector<float>(128 * 128, 0.0f));
  for (auto& m : masks)
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 64; ++x) m[std::size_t(y) * 128 + x] = 1.0f;
  const std::vector<glm::vec3> centres = {{-0.5f, 0, 0}, {0.6f, 0, 0}, {0, 0, 50}};  // left, right, out of view
  const auto g = glossy_from_masks(centres, cams, {&masks[0], &masks[1]});
  EXPECT_EQ(g, (std::vector<std::uint8_t>{1, 0, 0}));
  // One view is too few to call a Gaussian glossy (min_views = 2).
  const auto one = glossy_from_masks(centres, cams, {&masks[0], nullptr});
  EXPECT_EQ(one[0], 0);
  std::vector<float> wrong(10);
  EXPECT_THROW(glossy_from_masks(centres, cams, {&wrong, &masks[1]}), Error);
}

TEST(PlanarReflection, MirroringReflectsCentresAndCovariances) {
  GaussianModel m = make_model({{{0.3f, -0.2f, 0.5f}, 0.1f}, {{0.0f, 0.0f, 0.2f}, 0.1f}});
  float* ls = m.values(Param::LogScale);
  float* rot = m.values(Param::Rotation);
  ls[0] = std::log(0.3f), ls[1] = std::log(0.1f), ls[2] = std::log(0.02f);  // an anisotropic, tilted Gaussian
  const glm::quat q = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 0.5f)));
  rot[0] = q.w, rot[1] = q.x, rot[2] = q.y, rot[3] = q.z;
  MirrorPlane tilted;
  tilted.found = true;
  tilted.normal = glm::normalize(glm::dvec3(0.2, -0.1, 1.0));
  tilted.offset = 0.05;
  const SelectionMask first = {1, 0};
  GaussianModel mir = mirrored_through(m, first, tilted);
  ASSERT_EQ(mir.count(), 1u);
  const glm::vec3 n(tilted.normal);
  const glm::vec3 p(0.3f, -0.2f, 0.5f);
  const glm::vec3 expect = p - 2.0f * float(tilted.signed_distance(glm::dvec3(p))) * n;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mir.values(Param::Position)[k], expect[k], 1e-5f);
  const glm::mat3 M = glm::mat3(1.0f) - 2.0f * glm::outerProduct(n, n);
  const glm::mat3 want = M * covariance(ls, rot) * M, got = covariance(mir.values(Param::LogScale), mir.values(Param::Rotation));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(got[a][b], want[a][b], 1e-6f) << a << "," << b;
  EXPECT_NE(got[0][2], covariance(ls, rot)[0][2]);  // the mirror changed the orientation
}

TEST(PlanarReflection, ReflectionMaskIsTheMirroredTargetOnTheGlossySurface) {
  // A blob 0.4 above the floor z = 0 seen from above at an angle: its reflection lies below it in the image.
  GaussianModel target = make_model({{{0, 0, 0.4f}, 0.08f, 0.95f}});
  const Camera cam = look_at({0, -3, 1.5f}, {0, 0, 0});
  GaussianModel mirrored = mirrored_through(target, {1}, floor_plane());
  const std::vector<float> all(128 * 128, 1.0f), none(128 * 128, 0.0f);
  RasterSettings raster;
  const Mask m = planar_reflection_mask(mirrored, cam, all, raster, {0.2f, 0.0f});
  ASSERT_GT(count_set(m), 20u);
  // The mask's centre is where the mirrored centre (0, 0, -0.4) projects, not where the blob does.
  const glm::vec2 reflected = cam.project_camera(cam.to_camera({0, 0, -0.4f}));
  const glm::vec2 blob = cam.project_camera(cam.to_camera({0, 0, 0.4f}));
  double sx = 0, sy = 0, n = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      if (m(x, y)) sx += x + 0.5, sy += y + 0.5, ++n;
  EXPECT_NEAR(sx / n, reflected.x, 2.0);
  EXPECT_NEAR(sy / n, reflected.y, 2.0);
  EXPECT_GT(std::abs(sy / n - blob.y), 10.0);
  // Growing takes in more pixels, and nothing lies outside the glossy mask.
  EXPECT_GT(count_set(planar_reflection_mask(mirrored, cam, all, raster, {0.2f, 0.05f})), count_set(m));
  EXPECT_EQ(count_set(planar_reflection_mask(mirrored, cam, none, raster)), 0u);
}
