// The target's reflection in a planar glossy surface from geometry alone: the target mirrored through the
// plane (centres and covariances), and its coverage on the glossy surface as the reflection mask; the plane
// found from the glossy masks of several views.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/quaternion.hpp>

#include "render/raster/raster_types.h"
#include "core/util/error.h"
#include "core/scene/plane_from_masks.h"
#include "removal/masks/planar_reflection.h"
#include "removal/masks/removed_glossy_masks.h"
#include "train/loop/trainer.h"
#include "render/raster/rasterizer.h"
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

TEST(PlanarReflection, OnlyWhatStandsInFrontOfTheSurfaceIsReflected) {
  // A target above the floor z = 0 with a wide flat disc of its selection under the floor (a mirror world or
  // the floor's underside caught by its masks): the disc is not reflected, so the mask stays the target's
  // reflection and not a patch the disc's size at the target's foot.
  GaussianModel m = make_model({{{0, 0, 0.4f}, 0.08f, 0.95f}, {{0, 0, -0.1f}, 0.3f, 0.95f}, {{0.5f, 0, 0.2f}, 0.05f}});
  GaussianModel mirrored = mirrored_through(m, {1, 1, 0}, floor_plane());
  ASSERT_EQ(mirrored.count(), 1u);
  EXPECT_NEAR(mirrored.values(Param::Position)[2], -0.4f, 1e-6f);
  const Camera cam = look_at({0, -3, 1.5f}, {0, 0, 0});
  const std::vector<float> all(std::size_t(cam.width) * cam.height, 1.0f);
  RasterSettings raster;
  GaussianModel target_alone = mirrored_through(make_model({{{0, 0, 0.4f}, 0.08f, 0.95f}}), {1}, floor_plane());
  const Mask alone = planar_reflection_mask(target_alone, cam, all, raster, {0.2f, 0.0f});
  const Mask with_disc = planar_reflection_mask(mirrored, cam, all, raster, {0.2f, 0.0f});
  EXPECT_EQ(with_disc.data, alone.data);
  MirrorPlane below = floor_plane();
  below.offset = -0.2;  // the same disc now in front of a lower surface: reflected
  EXPECT_EQ(mirrored_through(m, {1, 1, 0}, below).count(), 2u);
  EXPECT_THROW(mirrored_through(m, {1, 1}, floor_plane()), Error);
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

TEST(PlanarReflection, ReflectionBehindTheTargetIsFoundOnTheSurfaceWithoutIt) {
  // A blob resting just above the floor z = 0, seen from low down: its reflection starts right below it,
  // partly behind the blob itself. The photo's glossy mask is 0 under the blob (the blob is not glossy),
  // so the mirrored blob's coverage there is lost; after the removal that surface (and whatever the model
  // shows through it) is seen, and the mask of the surface without the target finds it.
  GaussianModel target = make_model({{{0, 0, 0.12f}, 0.1f, 0.95f}});
  const Camera cam = look_at({0, -3, 0.6f}, {0, 0, 0});
  const std::size_t hw = std::size_t(cam.width) * cam.height;
  RasterSettings raster;
  const RasterOutput r = rasterize(target.view(false), cam, raster, target.device());
  const std::vector<float> alpha = r.gbuffer.alpha.to_host();
  TrainView view;
  view.name = "r_000";
  view.camera = cam;
  view.glossy_mask.assign(hw, 1.0f);  // the floor fills the view ...
  InpaintMaskView hole;
  hole.covered = Mask(cam.width, cam.height);
  for (std::size_t p = 0; p < hw; ++p)
    if (alpha[p] > 0.2f) view.glossy_mask[p] = 0.0f, hole.covered.data[p] = 255;  // ... except behind the blob
  ASSERT_GT(count_set(hole.covered), 50u);
  GaussianModel mirrored = mirrored_through(target, {1}, floor_plane());
  const Mask photo = planar_reflection_mask(mirrored, cam, view.glossy_mask, raster, {0.2f, 0.0f});
  const Mask removed = planar_reflection_mask(mirrored, cam, removed_glossy_mask(view, hole), raster, {0.2f, 0.0f});
  std::size_t behind = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    EXPECT_FALSE(photo.data[p] && hole.covered.data[p]) << "pixel " << p;  // the photo's mask never sees it
    if (photo.data[p]) EXPECT_TRUE(removed.data[p]) << "pixel " << p;       // the rest stays
    behind += removed.data[p] && hole.covered.data[p] ? 1 : 0;
  }
  EXPECT_GT(behind, 10u);
}

namespace {
// The glossy mask a camera sees of the disc of radius r at height h (z up): pixels whose ray meets the plane
// inside the disc.
std::vector<float> disc_mask(const Camera& c, double h, double r) {
  std::vector<float> m(std::size_t(c.width) * c.height, 0.0f);
  const glm::dvec3 eye(c.center());
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const glm::dvec3 d(c.ray_direction(x + 0.5f, y + 0.5f));
      if (d.z >= 0) continue;
      const double t = (h - eye.z) / d.z;
      const glm::dvec3 p = eye + t * d;
      if (std::hypot(p.x, p.y) < r) m[std::size_t(y) * c.width + x] = 1.0f;
    }
  return m;
}
}  // namespace

TEST(PlaneFromMasks, FindsTheHeightThatMapsTheViewsMasksOntoEachOther) {
  std::vector<Camera> cams;
  for (int k = 0; k < 10; ++k) {
    const float a = 0.6f * float(k);
    cams.push_back(look_at({4.0f * std::cos(a), 4.0f * std::sin(a), 2.5f + 0.2f * float(k % 3)}, {0, 0, 0.2f}));
  }
  EXPECT_NEAR(glm::dot(mean_camera_up(cams), glm::dvec3(0, 0, 1)), 1.0, 1e-3);
  for (double h : {0.0, 0.35}) {
    std::vector<std::vector<float>> masks;
    for (const Camera& c : cams) masks.push_back(disc_mask(c, h, 1.2));
    std::vector<const std::vector<float>*> ptrs;
    for (const auto& m : masks) ptrs.push_back(&m);
    const PlaneFromMasks p = plane_from_glossy_masks(cams, ptrs);
    ASSERT_TRUE(p.plane.found) << h;
    EXPECT_GT(p.iou, 0.9);
    EXPECT_NEAR(p.plane.offset, h, 0.03) << "the disc's height";
    EXPECT_GT(p.plane.normal.z, 0.99);
    EXPECT_GT(p.plane.tolerance, 0.0);
  }
  // No masks, or masks that agree at no height (noise): no plane.
  std::vector<const std::vector<float>*> none(cams.size(), nullptr);
  EXPECT_FALSE(plane_from_glossy_masks(cams, none).plane.found);
  std::vector<std::vector<float>> noise;
  for (std::size_t k = 0; k < cams.size(); ++k) {
    std::vector<float> m(128 * 128);
    std::mt19937 rng(unsigned(k) + 1u);
    for (float& v : m) v = float(rng() & 1u);
    noise.push_back(std::move(m));
  }
  std::vector<const std::vector<float>*> np;
  for (const auto& m : noise) np.push_back(&m);
  const PlaneFromMasks noisy = plane_from_glossy_masks(cams, np);
  EXPECT_FALSE(noisy.plane.found) << "IoU " << noisy.iou << " at " << noisy.plane.offset;
}

TEST(PlaneFromMasks, FindsATiltedSurface) {
  std::vector<Camera> cams;
  for (int k = 0; k < 10; ++k) {
    const float a = 0.6f * float(k);
    cams.push_back(look_at({4.0f * std::cos(a), 4.0f * std::sin(a), 2.5f}, {0, 0, 0.2f}));
  }
  // A disc on the plane through (0, 0, 0.1) tilted 4 degrees about x.
  const double tilt = 4.0 * 3.14159265358979323846 / 180.0;
  const glm::dvec3 n(0.0, -std::sin(tilt), std::cos(tilt));
  std::vector<std::vector<float>> masks;
  for (const Camera& c : cams) {
    std::vector<float> m(std::size_t(c.width) * c.height, 0.0f);
    const glm::dvec3 eye(c.center());
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        const glm::dvec3 d(c.ray_direction(x + 0.5f, y + 0.5f));
        const double t = (0.1 * n.z - glm::dot(eye, n)) / glm::dot(d, n);
        const glm::dvec3 p = eye + t * d - glm::dvec3(0, 0, 0.1);
        if (t > 0 && glm::length(p) < 1.2) m[std::size_t(y) * c.width + x] = 1.0f;
      }
    masks.push_back(std::move(m));
  }
  std::vector<const std::vector<float>*> ptrs;
  for (const auto& m : masks) ptrs.push_back(&m);
  const PlaneFromMasks p = plane_from_glossy_masks(cams, ptrs);
  ASSERT_TRUE(p.plane.found);
  EXPECT_LT(std::acos(std::min(1.0, glm::dot(p.plane.normal, n))) * 180.0 / 3.14159265358979323846, 1.5);
  EXPECT_NEAR(p.plane.signed_distance({0, 0, 0.1}), 0.0, 0.03);
}

TEST(PlaneFromMasks, WorldUpFromCamerasOnASector) {
  // Upright cameras on a 90-degree sector looking down at the scene: their up axes lean towards it, their
  // right axes are level.
  std::vector<Camera> cams;
  for (int k = 0; k < 6; ++k) {
    const float a = -2.4f + 0.3f * float(k);
    cams.push_back(look_at({5.0f * std::cos(a), 5.0f * std::sin(a), 3.0f}, {0, 0, 0}));
  }
  glm::dvec3 naive(0.0);
  for (const Camera& c : cams) naive -= glm::dvec3(c.R[0][1], c.R[1][1], c.R[2][1]);
  EXPECT_LT(glm::normalize(naive).z, 0.97) << "the mean of the up axes leans";
  EXPECT_GT(mean_camera_up(cams).z, 0.9999);
}

TEST(PlaneFromMasks, TargetRestsAboveItsReflection) {
  // A column standing on a glossy floor at z = 0 and its mirror world below, both selected (what a radiance
  // model of a mirror-like floor gives a mask selection): the band starts at the column's foot, not at its
  // reflection's.
  std::vector<Camera> cams;
  for (int k = 0; k < 10; ++k) {
    const float a = 0.6f * float(k);
    cams.push_back(look_at({4.0f * std::cos(a), 4.0f * std::sin(a), 2.5f}, {0, 0, 0.0f}, 128, 128, 120.0f));
  }
  const double radius = 0.15, height = 1.0;
  std::vector<std::vector<float>> masks;
  for (const Camera& c : cams) {
    std::vector<float> m = disc_mask(c, 0.0, 3.0);
    const glm::dvec3 eye(c.center());
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {  // the column in front of the floor is not glossy
        const glm::dvec3 d(c.ray_direction(x + 0.5f, y + 0.5f));
        for (double t = 0; t < 8.0; t += 0.01) {
          const glm::dvec3 p = eye + t * d;
          if (p.z >= 0 && p.z <= height && std::hypot(p.x, p.y) < radius) {
            m[std::size_t(y) * c.width + x] = 0.0f;
            break;
          }
        }
      }
    masks.push_back(std::move(m));
  }
  std::vector<const std::vector<float>*> ptrs;
  for (const auto& m : masks) ptrs.push_back(&m);
  std::vector<glm::vec3> centres;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 p(0.1f * u(rng), 0.1f * u(rng), 0.5f * float(height) * (1.0f + u(rng)));
    centres.push_back(p);
    centres.push_back({p.x, p.y, -p.z});  // its reflection
  }
  const std::vector<std::uint8_t> target(centres.size(), 1);
  const auto band = target_rest_heights(cams, ptrs, centres, target);
  ASSERT_TRUE(band.has_value());
  EXPECT_NEAR(band->high, 0.0, 0.1) << "the column's foot";
  EXPECT_LT(band->low, band->high);
  ASSERT_TRUE(band->preferred.has_value());
  EXPECT_DOUBLE_EQ(*band->preferred, band->high);
  // Every selected Gaussian counts without masks to tell them apart: the band would start in the reflection.
  std::vector<const std::vector<float>*> none(cams.size(), nullptr);
  const auto blind = target_rest_heights(cams, none, centres, target);
  ASSERT_TRUE(blind.has_value());
  EXPECT_LT(blind->high, -0.8);
  // Fewer than ten Gaussians: no band.
  const std::vector<glm::vec3> few(centres.begin(), centres.begin() + 8);
  EXPECT_FALSE(target_rest_heights(cams, ptrs, few, std::vector<std::uint8_t>(few.size(), 1)).has_value());
}
