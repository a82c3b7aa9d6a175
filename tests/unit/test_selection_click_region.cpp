// The two-click selection: a click's region stops at a depth step (an object nearer than the floor it
// stands on, of nearly the same colour) and at a colour edge (a flat decal), on constructed images; the
// regions are lifted to the Gaussians by rendered weight, which keeps the object's border where centres
// lose it (the table-and-box scene).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/util/error.h"
#include "removal/selection/gaussian_pixel_weights.h"
#include "removal/selection/selection_click_region.h"
#include "removal/selection/selection_masks.h"
#include "removal/selection/selection_view_masks.h"
#include "tests/support/table_box_scene.h"

namespace goris {
namespace {

constexpr int kW = 64, kH = 64;

bool in_square(int x, int y, int x0, int y0, int x1, int y1) { return x >= x0 && x < x1 && y >= y0 && y < y1; }

Image photo_with_square(float r_in, float r_out, int x0, int y0, int x1, int y1) {
  Image img(kW, kH, 3);
  float* p = img.pixels.data();
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      // A little deterministic texture on both, below the ladder's first rungs.
      const float t = 0.01f * float((x * 7 + y * 13) % 5);
      const float v = in_square(x, y, x0, y0, x1, y1) ? r_in : r_out;
      float* c = p + 3 * (std::size_t(y) * kW + std::size_t(x));
      c[0] = v + t, c[1] = 0.5f + t, c[2] = 0.4f;
    }
  return img;
}

double iou_with_square(const Mask& m, int x0, int y0, int x1, int y1) {
  std::size_t inter = 0, uni = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool a = m(x, y), b = in_square(x, y, x0, y0, x1, y1);
      inter += a && b;
      uni += a || b;
    }
  return uni ? double(inter) / double(uni) : 1.0;
}

TEST(ClickRegion, StopsAtADepthStepOfAnObjectOfTheFloorsColour) {
  // The object is 0.03 redder than the floor (inside every tolerance rung but the first) and 5 % nearer.
  const Image photo = photo_with_square(0.53f, 0.50f, 20, 20, 40, 44);
  std::vector<float> depth(kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      depth[std::size_t(y) * kW + x] = in_square(x, y, 20, 20, 40, 44) ? 4.75f : 5.0f + 0.002f * float(y);
  const ClickRegion r = grow_click_region(photo, depth, 30, 30);
  EXPECT_EQ(r.area, std::size_t(20 * 24));
  EXPECT_DOUBLE_EQ(iou_with_square(r.mask, 20, 20, 40, 44), 1.0);
}

TEST(ClickRegion, StopsAtAColourEdgeOnOneSurface) {
  // A flat decal (same depth as the floor) of a clearly different colour: the ladder stops before the
  // tolerance that would swallow the floor.
  const Image photo = photo_with_square(0.9f, 0.3f, 10, 12, 30, 28);
  std::vector<float> depth(kW * kH, 5.0f);
  const ClickRegion r = grow_click_region(photo, depth, 15, 20);
  EXPECT_DOUBLE_EQ(iou_with_square(r.mask, 10, 12, 30, 28), 1.0);
  EXPECT_FALSE(r.leaked_at_first);
  // Clicking the floor takes the floor, not the decal.
  const ClickRegion f = grow_click_region(photo, depth, 2, 2);
  EXPECT_FALSE(f.mask(15, 20));
}

TEST(ClickRegion, AGlossyBarrierKeepsTheFillOnATexturedTargetStandingOnTheSurface) {
  // A two-colour target (R 0.3 on three quarters, 0.6 on the rest) on a floor of R 0.45 at the same depth
  // (its foot runs on into the floor): from the darker part the fill reaches the floor (0.15 away) before
  // the lighter part (0.3 away), and the ladder stops at the darker part.
  Image photo(kW, kH, 3);
  float* p = photo.pixels.data();
  std::vector<float> glossy(kW * kH, 0.0f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool target = in_square(x, y, 20, 20, 44, 44);
      float* c = p + 3 * (std::size_t(y) * kW + std::size_t(x));
      c[0] = target ? (x < 38 ? 0.3f : 0.6f) : 0.45f, c[1] = 0.5f, c[2] = 0.4f;
      glossy[std::size_t(y) * kW + std::size_t(x)] = target ? 0.0f : 1.0f;
    }
  const std::vector<float> depth(kW * kH, 5.0f);
  const ClickRegion plain = grow_click_region(photo, depth, 25, 30);
  EXPECT_DOUBLE_EQ(iou_with_square(plain.mask, 20, 20, 38, 44), 1.0);
  // With the floor as the barrier (its glossy mask) the ladder climbs on and takes the whole target.
  const ClickRegion barred = grow_click_region(photo, depth, 25, 30, {}, &glossy);
  EXPECT_DOUBLE_EQ(iou_with_square(barred.mask, 20, 20, 44, 44), 1.0);
  const std::vector<float> wrong_size(10, 0.0f);
  EXPECT_THROW(grow_click_region(photo, depth, 25, 30, {}, &wrong_size), Error);
}

TEST(ClickRegion, NoDepthUnderTheClickIsAnEmptyRegionAndBadInputsThrow) {
  const Image photo = photo_with_square(0.9f, 0.3f, 10, 12, 30, 28);
  std::vector<float> depth(kW * kH, 0.0f);
  EXPECT_EQ(grow_click_region(photo, depth, 15, 20).area, 0u);
  EXPECT_THROW(grow_click_region(photo, depth, kW, 0), Error);
  EXPECT_THROW(grow_click_region(photo, std::vector<float>(10, 1.0f), 1, 1), Error);
}

// The region a click grows stops a little short of the object's silhouette (the photo's anti-aliased edge,
// the render's soft depth edge), so the large Gaussians at the object's border have their centres just
// outside it: voting by centres loses them, voting by rendered weight keeps them.
TEST(ClickRegionLift, WeightKeepsTheBorderThatCentresLose) {
  constexpr int kShort = 1;
  // The table of table_and_box with a box of large Gaussians (a short run's): 0.1 apart on a box 0.4 wide.
  test::SceneBuilder scene = test::table_and_box(0.0f, 0.0f);
  for (float x = -test::kHalf + 0.05f; x < test::kHalf; x += 0.1f)
    for (float y = -test::kHalf + 0.05f; y < test::kHalf; y += 0.1f)
      for (float z = 0.05f; z < 0.4f; z += 0.1f) scene.add({x, y, z}, glm::vec3(0.05f), 0.2f, true);
  const GaussianModel model = scene.model();
  const std::vector<Camera> all = test::table_cameras();
  const std::vector<Camera> cams = {all[0], all[3]};
  std::vector<ClickView> views;
  for (std::size_t v = 0; v < cams.size(); ++v) {
    const Mask exact = selection_view_mask(model, scene.target, cams[v]);
    // kShort pixels short of the silhouette: the erosion as the complement's dilation.
    Mask outside(exact.width, exact.height);
    for (std::size_t p = 0; p < outside.data.size(); ++p) outside.data[p] = exact.data[p] ? 0 : 255;
    const Mask grown_out = dilate_mask(outside, kShort);
    Mask region(exact.width, exact.height);
    for (std::size_t p = 0; p < region.data.size(); ++p) region.data[p] = grown_out.data[p] ? 0 : 255;
    ASSERT_GT(count_set(region), 20u);
    views.push_back({"v" + std::to_string(v), cams[v], region});
  }
  // The target Gaussians the clicked views show at all (the others are for the closing).
  std::vector<Mask> full;
  for (const Camera& c : cams) {
    Mask m(c.width, c.height);
    m.data.assign(m.data.size(), 255);
    full.push_back(m);
  }
  const PixelWeights shown = gaussian_pixel_weights(model, cams, full, {});
  std::size_t visible_target = 0;
  for (std::size_t k = 0; k < scene.target.size(); ++k) visible_target += scene.target[k] && shown.inside[k] >= 0.5f;
  ASSERT_GT(visible_target, 30u);

  auto score = [&](const SelectionMask& sel, std::size_t& target, std::size_t& table) {
    target = table = 0;
    for (std::size_t k = 0; k < sel.size(); ++k)
      if (sel[k]) ++(scene.target[k] ? target : table);
  };
  std::size_t w_target = 0, w_table = 0, c_target = 0, c_table = 0;
  score(select_from_click_regions(model, views), w_target, w_table);
  std::vector<MaskedView> masked;
  for (const ClickView& v : views) masked.push_back({v.name, v.camera, mask_to_image(v.region)});
  MaskVoteSettings centres;
  centres.min_fraction = 1.0f;
  score(labels_from_masks(model, masked, centres, {}).selected, c_target, c_table);
  // Centres: 20 of the 56 target Gaussians the views show; weight: all of them (60: a few more that show
  // less than half a pixel). The table's Gaussians at the box's foot draw a tenth of their weight inside
  // both regions and come too (32 of them): the every-view vote (revote_with_view_masks) is what drops them,
  // and centres take none.
  EXPECT_GE(double(w_target), 0.9 * double(visible_target));
  EXPECT_LE(double(c_target), 0.4 * double(visible_target));
  EXPECT_EQ(c_table, 0u);
  EXPECT_LT(w_table, w_target);
}

}  // namespace
}  // namespace goris
