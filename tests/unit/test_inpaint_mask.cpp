// The inpainting mask on a hand-built scene: a flat table of Gaussians (z = 0) with a box on it (the
// target), seen from straight above and from eight oblique cameras around it. The table under a box that
// RESTS on it is hidden from every camera (in the mask); the table around the box that the top view
// cannot see past the box's top is seen by the oblique cameras (not in the mask); under a FLOATING box
// the oblique cameras see the whole table, so the top view's mask is empty.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/masks/inpaint_mask.h"
#include "removal/masks/inpaint_mask_scene.h"
#include "tests/support/table_box_scene.h"

namespace goris {
namespace {

using test::SceneBuilder;
using test::table_and_box;
using test::kHalf;
const auto cameras = test::table_cameras;

// Where the ray through pixel (x, y) of camera c meets the table plane z = 0.
glm::vec3 table_hit(const Camera& c, int x, int y) {
  const glm::vec3 d = c.ray_direction(float(x) + 0.5f, float(y) + 0.5f), o = c.center();
  return o + d * (-o.z / d.z);
}

float chebyshev(const glm::vec3& p) { return std::max(std::fabs(p.x), std::fabs(p.y)); }

TEST(InpaintMask, RestingBoxHidesItsFootprintFromEveryView) {
  const SceneBuilder s = table_and_box(0.0f, 1.0f);
  const std::vector<Camera> cams = cameras();
  const auto masks = compute_inpaint_masks(s.model(), s.target, cams);
  ASSERT_EQ(masks.size(), cams.size());

  // Top view: the deep footprint (table points well inside |x|, |y| < 0.2) is covered and masked; the
  // ring between the footprint and what the box's top hides (0.2 .. 0.33) is covered but NOT masked.
  const InpaintMaskView& top = masks[0];
  std::size_t deep = 0, ring = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const float r = chebyshev(table_hit(cams[0], x, y));
      if (r < 0.12f) {
        ++deep;
        EXPECT_TRUE(top.covered(x, y)) << x << "," << y;
        EXPECT_TRUE(top.mask(x, y)) << "pixel " << x << "," << y << " (table point at " << r << ")";
      } else if (r > 0.27f && r < 0.31f && top.covered(x, y)) {
        ++ring;
        EXPECT_FALSE(top.mask(x, y)) << "pixel " << x << "," << y << " (table point at " << r << ") is seen by the oblique views";
      }
    }
  EXPECT_GT(deep, 50u);
  EXPECT_GT(ring, 40u);
  EXPECT_GT(top.stats.covered, top.stats.masked);
  EXPECT_EQ(top.stats.empty_behind, 0u);

  // Every view: a masked pixel's surface lies in the footprint; the oblique views have masks too.
  for (std::size_t v = 0; v < masks.size(); ++v) {
    const InpaintMaskView& m = masks[v];
    EXPECT_EQ(m.mask.width, 64);
    if (v > 0) EXPECT_GT(m.stats.masked, 5u) << "view " << v;
    EXPECT_EQ(m.stats.empty_behind, 0u) << "view " << v;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        if (!m.mask(x, y)) continue;
        EXPECT_TRUE(m.covered(x, y));
        const float z = m.removed_depth.pixels[std::size_t(y) * 64 + x];
        ASSERT_GT(z, 0.0f);
        const glm::vec3 X = back_project(cams[v], x, y, z);
        EXPECT_NEAR(X.z, 0.0f, 0.03f) << "view " << v;
        EXPECT_LT(chebyshev(X), kHalf + 0.08f) << "view " << v << " pixel " << x << "," << y;
      }
  }
}

TEST(InpaintMask, FloatingBoxLeavesNothingUnseenBelowIt) {
  // Lifted to z in [0.6, 1.0]: the oblique cameras see the whole table under it.
  const SceneBuilder s = table_and_box(0.6f, 1.0f);
  const std::vector<Camera> cams = cameras();
  const auto masks = compute_inpaint_masks(s.model(), s.target, cams);
  EXPECT_GT(masks[0].stats.covered, 300u);  // the box still covers the middle of the top view
  EXPECT_EQ(masks[0].stats.masked, 0u);
  // A point that the top view cannot see through the box is seen by the oblique views, so no raw pixel
  // survives anywhere in the top view.
  EXPECT_EQ(masks[0].stats.raw, 0u);
}

TEST(InpaintMask, NothingBehindTheTargetIsAHole) {
  // The table has a hole under the box: the top view sees no surface behind the box's middle.
  const SceneBuilder s = table_and_box(0.0f, 1.0f, /*hole_in_table=*/true);
  const std::vector<Camera> cams = cameras();
  const auto masks = compute_inpaint_masks(s.model(), s.target, cams);
  EXPECT_GT(masks[0].stats.empty_behind, 50u);
  EXPECT_TRUE(masks[0].mask(32, 32));
  EXPECT_EQ(masks[0].removed_depth.pixels[32 * 64 + 32], 0.0f);
  EXPECT_GT(masks[0].target_depth.pixels[32 * 64 + 32], 1.4f);  // the box's top, 1.5 below the camera

  InpaintMaskSettings keep_empty;
  keep_empty.empty_behind_is_hole = false;
  const auto masks2 = compute_inpaint_masks(s.model(), s.target, cams, keep_empty);
  EXPECT_FALSE(masks2[0].mask(32, 32));
}

TEST(InpaintMask, SplitAndBadInput) {
  const SceneBuilder s = table_and_box(0.0f, 1.0f);
  const GaussianModel model = s.model();
  const SplitScene split = split_removed(model, s.target);
  std::size_t n_target = 0;
  for (auto t : s.target) n_target += t;
  EXPECT_EQ(split.target.count(), n_target);
  EXPECT_EQ(split.kept.count(), model.count() - n_target);
  // The first kept Gaussian is the first table Gaussian, the first target one the first box Gaussian.
  EXPECT_EQ(split.kept.tensor(Param::Position).value[0], s.pos[0]);
  const std::size_t first_box = model.count() - n_target;
  EXPECT_EQ(split.target.tensor(Param::Position).value[2], s.pos[first_box * 3 + 2]);

  const std::vector<Camera> cams = cameras();
  EXPECT_THROW(compute_inpaint_masks(model, std::vector<std::uint8_t>(model.count(), 0), cams), Error);
  EXPECT_THROW(compute_inpaint_masks(model, std::vector<std::uint8_t>(model.count(), 1), cams), Error);
  EXPECT_THROW(compute_inpaint_masks(model, std::vector<std::uint8_t>(3, 1), cams), Error);
  EXPECT_THROW(compute_inpaint_masks(model, s.target, {}), Error);

  // The overload taking the full model agrees with the one taking the split.
  const std::vector<Camera> two = {cams[0], cams[1]};
  const auto a = compute_inpaint_masks(model, s.target, two);
  const auto b = compute_inpaint_masks(split.kept, split.target, two);
  EXPECT_EQ(a[0].mask.data, b[0].mask.data);
  EXPECT_EQ(a[1].mask.data, b[1].mask.data);
}

TEST(InpaintMask, BackProjectionInvertsProjection) {
  const Camera c = cameras()[3];
  const glm::vec3 X = back_project(c, 17, 40, 2.75f);
  const glm::vec3 pc = c.to_camera(X);
  EXPECT_NEAR(pc.z, 2.75f, 1e-5f);
  const glm::vec2 uv = c.project_camera(pc);
  EXPECT_NEAR(uv.x, 17.5f, 1e-3f);
  EXPECT_NEAR(uv.y, 40.5f, 1e-3f);
}

}  // namespace
}  // namespace goris
