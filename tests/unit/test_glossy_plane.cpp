// The glossy plane constraint (train/loop/glossy_plane.h): on a table of flat Gaussians seen from above, the
// plane is the table top with its normal towards the cameras, even when a larger tilted mirror world lies
// under it; the mirror world under the table goes at the start, a Gaussian that moves under the table later
// is put back on it, and what lies under the plane away from the glossy pixels (a leg) or above it (an
// object) is left alone. Without glossy masks nothing happens.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/scene/selection_points.h"
#include "tests/support/intrinsic_scene.h"
#include "tests/unit/test_selection_scene.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/glossy_plane.h"
#include "train/loop/trainer.h"

namespace goris {
namespace {

constexpr int kSize = 64;
constexpr float kTable = 1.0f;  // the table top is z = 0, |x|, |y| <= kTable
constexpr float kThickness = 0.2f;  // its side, glossy too, goes down to z = -kThickness

// A camera above the table looking at its centre; its glossy mask holds the pixels whose ray meets the top.
TrainView view_from(glm::vec3 eye) {
  TrainView v;
  v.camera = test::look_at(eye, {0.0f, 0.0f, 0.0f}, kSize, kSize, 40.0f);
  const Camera& c = v.camera;
  v.glossy_mask.assign(std::size_t(kSize) * kSize, 0.0f);
  const glm::mat3 to_world = glm::transpose(c.R);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 d = to_world * glm::vec3((float(x) + 0.5f - c.cx) / c.fx, (float(y) + 0.5f - c.cy) / c.fy, 1.0f);
      // The ray meets the table, a slab kThickness deep (top or side): slab intersection per axis.
      float t0 = 0.0f, t1 = 1e30f;
      const glm::vec3 lo(-kTable, -kTable, -kThickness), hi(kTable, kTable, 0.0f);
      for (int a = 0; a < 3; ++a) {
        const float ta = (lo[a] - eye[a]) / d[a], tb = (hi[a] - eye[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
      }
      if (t0 <= t1) v.glossy_mask[std::size_t(y) * kSize + std::size_t(x)] = 1.0f;
    }
  return v;
}

struct Scene {
  std::vector<TrainView> views;
  GaussianModel model;
  std::size_t table = 0, mirror = 0, leg = 0, object = 0, side = 0;  // counts, in this order in the model
};

// `extra` Gaussians follow the side in the model.
Scene table_scene(const std::vector<test::TestGaussian>& extra = {}) {
  Scene s;
  for (glm::vec3 eye : {glm::vec3(2.0f, 2.0f, 3.0f), glm::vec3(-2.0f, 2.0f, 3.0f), glm::vec3(2.0f, -2.0f, 3.0f),
                        glm::vec3(-2.0f, -2.0f, 3.0f)})
    s.views.push_back(view_from(eye));
  std::vector<test::TestGaussian> gs;
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j) gs.push_back({{-0.9f + 0.128f * float(i), -0.9f + 0.128f * float(j), 0.0f}});
  s.table = gs.size();
  for (int i = 0; i < 6; ++i)  // the mirror world: an object's copy under the table
    for (int j = 0; j < 6; ++j) gs.push_back({{-0.3f + 0.1f * float(i), -0.3f + 0.1f * float(j), -0.3f}});
  s.mirror = gs.size() - s.table;
  for (int k = 0; k < 5; ++k) gs.push_back({{2.0f, 0.0f, -0.1f * float(k + 1)}});  // a leg off the table's edge
  s.leg = 5;
  for (int k = 0; k < 10; ++k) gs.push_back({{0.05f * float(k) - 0.2f, 0.0f, 0.3f}});  // the object
  s.object = 10;
  for (int k = 0; k < 6; ++k)  // the table's own side, under the plane at the outline of its top
    gs.push_back({{k % 2 ? -kTable : 0.95f * kTable, 0.1f * float(k / 2) - 0.1f, -0.05f - 0.05f * float(k / 2)}});
  s.side = 6;
  gs.insert(gs.end(), extra.begin(), extra.end());
  s.model = test::make_model(gs);
  float* ls = s.model.values(Param::LogScale);
  for (std::size_t i = 0; i < s.table; ++i) ls[3 * i + 2] = std::log(0.004f);  // flat, normal +z
  return s;
}

TEST(GlossyPlane, PrunesTheMirrorWorldAndKeepsCentresOnTheCamerasSide) {
  Scene s = table_scene();
  const std::vector<std::uint8_t> over = over_glossy_pixels(s.model, s.views);
  for (std::size_t i = 0; i < s.table + s.mirror; ++i) EXPECT_EQ(over[i], 1) << "table or mirror world " << i;
  for (std::size_t i = s.table + s.mirror; i < s.table + s.mirror + s.leg; ++i) EXPECT_EQ(over[i], 0) << "leg " << i;
  for (std::size_t i = over.size() - s.side; i < over.size(); ++i) EXPECT_EQ(over[i], 1) << "side " << i;

  GlossyPlaneConstraint constraint;
  const std::string note = constraint.start(s.model, s.views);
  ASSERT_TRUE(constraint.plane().found) << note;
  EXPECT_GT(constraint.plane().normal.z, 0.999) << "turned towards the cameras";
  EXPECT_NEAR(constraint.plane().offset, 0.0, 1e-4);
  EXPECT_EQ(constraint.pruned(), s.mirror) << note << ": the side, under the plane over glossy pixels, stays";
  ASSERT_EQ(s.model.count(), s.table + s.leg + s.object + s.side);
  EXPECT_NE(note.find("pruned 36 of"), std::string::npos) << note;
  // The masks' level plane lies below the top (its glossy side pulls it down); the top's Gaussians place it.
  EXPECT_NE(note.find("from the glossy masks, level, moved +0.0"), std::string::npos) << note;

  // A table Gaussian sinks under the top, the leg moves: only the first is put back (at -tolerance / 2).
  constexpr std::size_t kCentre = 7 * 15 + 7;  // the table's middle Gaussian
  float* pos = s.model.values(Param::Position);
  pos[3 * kCentre + 2] = -0.2f;
  const std::size_t leg0 = s.table;
  pos[3 * leg0 + 2] = -0.45f;
  EXPECT_EQ(constraint.apply(s.model, s.views, 4001, false).moved, 1u);
  pos = s.model.values(Param::Position);
  EXPECT_NEAR(pos[3 * kCentre + 2], -0.5 * constraint.plane().tolerance, 1e-6);
  EXPECT_FLOAT_EQ(pos[3 * leg0 + 2], -0.45f);
  EXPECT_FLOAT_EQ(pos[3 * (s.table + s.leg) + 2], 0.3f);
  EXPECT_EQ(constraint.apply(s.model, s.views, 4002, false).moved, 0u) << "nothing left beyond the plane";
  // With prune_sinkers the Gaussian put back goes at the next refresh, and nothing else does.
  pos = s.model.values(Param::Position);
  pos[3 * kCentre + 2] = -0.2f;
  const std::size_t count = s.model.count();
  EXPECT_EQ(constraint.apply(s.model, s.views, 4003, true).moved, 1u);
  EXPECT_EQ(constraint.apply(s.model, s.views, 4050, true).pruned, 0u) << "not due yet";
  const int due_at = 4001 + GlossyPlaneConstraint::kRefreshInterval;
  const GlossyPlaneConstraint::Step due = constraint.apply(s.model, s.views, due_at, true);
  EXPECT_EQ(due.pruned, 1u);
  EXPECT_EQ(due.moved, 0u);
  EXPECT_EQ(s.model.count(), count - 1);
  EXPECT_EQ(constraint.sinkers_pruned(), 1u);
}

TEST(GlossyPlane, TheFootprintFillsTheTopsHolesButLeavesItsSide) {
  // After the warm-up the top can be sparse where it shows reflections: lift the table Gaussians over the
  // mirror world out of the plane (a 7 x 7 hole). The mirror world, under the hole, still goes; the side,
  // under the outline, stays.
  Scene s = table_scene();
  float* pos = s.model.values(Param::Position);
  std::size_t lifted = 0;
  for (std::size_t i = 0; i < s.table; ++i)
    if (std::abs(pos[3 * i]) < 0.45f && std::abs(pos[3 * i + 1]) < 0.45f) pos[3 * i + 2] = 0.5f, ++lifted;
  ASSERT_EQ(lifted, 49u);
  GlossyPlaneConstraint constraint;
  const std::string note = constraint.start(s.model, s.views);
  ASSERT_TRUE(constraint.plane().found) << note;
  EXPECT_EQ(constraint.pruned(), s.mirror) << note;
  EXPECT_EQ(s.model.count(), s.table + s.leg + s.object + s.side);
}

TEST(GlossyPlane, ThePlaneComesFromTheMasksNotFromATiltedMirrorWorld) {
  // The warm-up of a mirror-like top holds more flat Gaussians in its mirror world than on the top: here a
  // 20 x 20 sheet under the table tilted 25 degrees about x. Fitted to the flat Gaussians over glossy pixels,
  // the plane would be the sheet's; the masks give the top, the top's Gaussians its exact height, and the
  // whole sheet lies beyond it.
  std::vector<test::TestGaussian> gs;
  const float t = glm::radians(25.0f);
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      const float u = -0.6f + 0.06f * float(i), v = -0.6f + 0.06f * float(j);
      gs.push_back({{u, v * std::cos(t), -0.45f + v * std::sin(t)}});
    }
  Scene s = table_scene(gs);
  const std::size_t sheet0 = s.model.count() - gs.size();
  float* ls = s.model.values(Param::LogScale);
  float* rot = s.model.values(Param::Rotation);
  for (std::size_t i = sheet0; i < s.model.count(); ++i) {
    ls[3 * i + 2] = std::log(0.004f);
    rot[4 * i] = std::cos(0.5f * t), rot[4 * i + 1] = std::sin(0.5f * t), rot[4 * i + 2] = rot[4 * i + 3] = 0.0f;
  }
  ASSERT_NEAR(std::abs(flat_normals(s.model)[sheet0].z), std::cos(t), 1e-5) << "the sheet is flat and tilted";
  const std::vector<std::uint8_t> over = over_glossy_pixels(s.model, s.views);
  for (std::size_t i = sheet0; i < s.model.count(); ++i) ASSERT_EQ(over[i], 1) << "the sheet is seen through the top";

  GlossyPlaneConstraint constraint;
  const std::string note = constraint.start(s.model, s.views);
  ASSERT_TRUE(constraint.plane().found) << note;
  EXPECT_GT(constraint.plane().normal.z, std::cos(glm::radians(1.0))) << note;
  EXPECT_NEAR(constraint.plane().offset, 0.0, 1e-4) << note << ": the top's Gaussians place it";
  EXPECT_EQ(constraint.pruned(), s.mirror + gs.size()) << note;
}

TEST(GlossyPlane, WithoutASurfaceLayerThePlaneStaysAtTheMasksHeight) {
  // A floor's warm-up can still be a fog: spread the table's Gaussians evenly through +-0.15 around the top.
  // No layer holds a third of them, so the plane stays where the masks put it (below the top: the glossy
  // side pulls the masks' outline down) and the log line says it was not moved.
  Scene s = table_scene();
  float* pos = s.model.values(Param::Position);
  for (std::size_t i = 0; i < s.table; ++i) pos[3 * i + 2] = -0.15f + 0.3f * float((i * 7) % s.table) / float(s.table);
  GlossyPlaneConstraint constraint;
  const std::string note = constraint.start(s.model, s.views);
  ASSERT_TRUE(constraint.plane().found) << note;
  EXPECT_NE(note.find("from the glossy masks, level: n ="), std::string::npos) << note;
  EXPECT_LT(constraint.plane().offset, -0.03) << note << ": the masks' height, not the top's";
  EXPECT_GT(constraint.plane().offset, -0.1) << note;
}

TEST(GlossyPlane, AlignsTheTablesFlatGaussiansToThePlaneOnly) {
  Scene s = table_scene();
  GlossyPlaneConstraint constraint;
  constraint.start(s.model, s.views);
  ASSERT_TRUE(constraint.plane().found);
  const std::size_t leg0 = s.table, object0 = s.table + s.leg;
  // Tilt table Gaussian 3 by 4 degrees about x (its stored quaternion scaled by 2: the length is kept), make
  // the leg and the object flat and tilted too: only the table Gaussian, in the band over glossy pixels, turns.
  const float half = 0.5f * glm::radians(4.0f);
  const glm::quat tilt(std::cos(half), std::sin(half), 0.0f, 0.0f);
  float* rot = s.model.values(Param::Rotation);
  float* ls = s.model.values(Param::LogScale);
  for (std::size_t i : {std::size_t(3), leg0, object0}) {
    rot[4 * i] = 2.0f * tilt.w, rot[4 * i + 1] = 2.0f * tilt.x, rot[4 * i + 2] = 0.0f, rot[4 * i + 3] = 0.0f;
    ls[3 * i + 2] = std::log(0.004f);
  }
  ls[3 * 3 + 0] = std::log(0.05f), ls[3 * 3 + 1] = std::log(0.02f);  // anisotropic in the plane
  const std::vector<float> scales_before(ls, ls + 3 * s.model.count());
  const glm::vec3 in_plane_before = glm::mat3_cast(tilt)[0];
  EXPECT_EQ(constraint.apply(s.model, s.views, 4001, false).moved, 0u);
  EXPECT_EQ(constraint.align_normals(s.model), 1u);
  EXPECT_EQ(constraint.align_normals(s.model), 0u) << "already aligned";

  const std::vector<glm::vec3> normals = flat_normals(s.model);
  EXPECT_GT(std::abs(normals[3].z), 1.0f - 1e-6f) << "table Gaussian 3 now has the plane's normal";
  EXPECT_NEAR(std::abs(normals[leg0].z), std::cos(glm::radians(4.0f)), 1e-5) << "the leg is off the glossy pixels";
  EXPECT_NEAR(std::abs(normals[object0].z), std::cos(glm::radians(4.0f)), 1e-5) << "the object is off the plane";
  rot = s.model.values(Param::Rotation);
  const glm::quat q(rot[12], rot[13], rot[14], rot[15]);
  EXPECT_NEAR(glm::length(q), 2.0f, 1e-5) << "the stored length is kept";
  // The shortest turn: the long in-plane axis (x) stays where it was, it was already in the plane.
  EXPECT_GT(glm::dot(glm::mat3_cast(glm::normalize(q))[0], in_plane_before), 1.0f - 1e-6f);
  ls = s.model.values(Param::LogScale);
  for (std::size_t k = 0; k < scales_before.size(); ++k) EXPECT_EQ(ls[k], scales_before[k]) << "scales untouched";
}

TEST(GlossyPlane, WithoutGlossyMasksNothingIsFoundOrMoved) {
  Scene s = table_scene();
  for (TrainView& v : s.views) v.glossy_mask.clear();
  GlossyPlaneConstraint constraint;
  const std::string note = constraint.start(s.model, s.views);
  EXPECT_TRUE(constraint.started());
  EXPECT_FALSE(constraint.plane().found);
  EXPECT_NE(note.find("none found"), std::string::npos) << note;
  EXPECT_EQ(s.model.count(), s.table + s.mirror + s.leg + s.object + s.side);
  EXPECT_EQ(constraint.apply(s.model, s.views, 4001, true).moved, 0u);
}

TEST(GlossyPlane, TheTrainerPrunesAtShadingStartAndHoldsTheFloorAfterwards) {
  // floor_and_blob: a flat glossy floor at z = 0 under a rough blob. Eight Gaussians under the floor's
  // centre play the mirror world (the depth-based prune is off, so only the plane can remove them).
  TrainConfig cfg = test::intrinsic_config(8);
  cfg.intrinsic.warmup = 4;
  cfg.intrinsic.prune_mirror_world = 0;
  cfg.intrinsic.glossy_plane = true;
  cfg.densify.from_iter = 1 << 30;
  cfg.densify.until_iter = 0;
  cfg.densify.opacity_reset_interval = 1 << 30;
  ASSERT_EQ(cfg.shading_from(), 4);
  const std::vector<TrainView> views = test::shaded_views(cfg, test::floor_and_blob(4));
  GaussianModel start = test::perturbed_start();
  const std::size_t floor_count = 64, before = start.count();
  GaussianModel with_mirror(Device::CPU);
  with_mirror.allocate(before + 8);
  for (int p = 0; p < kParamCount; ++p) {  // copies of blob Gaussian 70 appended
    const ParamTensor& src = start.tensor(Param(p));
    std::vector<float> v = src.value.to_host();
    const std::vector<float> one(v.begin() + 70 * src.width, v.begin() + 71 * src.width);
    for (int k = 0; k < 8; ++k) v.insert(v.end(), one.begin(), one.end());
    with_mirror.tensor(Param(p)).value.upload(v.data(), v.size());
  }
  with_mirror.sh_degree = start.sh_degree;
  with_mirror.max_sh_degree = start.max_sh_degree;
  float* pos = with_mirror.values(Param::Position);
  for (int k = 0; k < 8; ++k) {
    float* p = pos + 3 * (before + std::size_t(k));
    p[0] = -0.15f + 0.1f * float(k % 4), p[1] = -0.1f + 0.2f * float(k / 4), p[2] = -0.3f;
  }
  auto renderer = std::make_shared<IntrinsicRenderer>(cfg, 3.0f, Device::CPU);
  Trainer t(cfg, views, 3.0f, renderer, Trainer::initial_state(cfg, std::move(with_mirror)));
  std::string note;
  while (t.state().iteration < 4) note += t.step().densify_note;
  EXPECT_NE(note.find(", 1.000), n . x = 0.000"), std::string::npos) << note;
  EXPECT_NE(note.find("pruned 8 of 84"), std::string::npos) << note;
  ASSERT_EQ(t.model().count(), before);
  // A floor Gaussian pushed under the floor is back on it after the next update.
  t.model().values(Param::Position)[3 * 10 + 2] = -0.25f;
  t.step();
  const float z = t.model().values(Param::Position)[3 * 10 + 2];
  EXPECT_GT(z, -0.05f);
  EXPECT_LT(z, 0.05f);
  for (std::size_t i = 0; i < floor_count; ++i) EXPECT_GT(t.model().values(Param::Position)[3 * i + 2], -0.05f) << i;
}

}  // namespace
}  // namespace goris
