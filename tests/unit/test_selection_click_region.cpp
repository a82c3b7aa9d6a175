// The two-click selection's 2D part and the mask writer's photo edges, on constructed images: a click's
// region stops at a depth step (an object nearer than the floor it stands on, of nearly the same colour)
// and at a colour edge (a flat decal), and the GrabCut refinement moves a displaced, swollen coverage mask
// back onto the photo's square.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/util/error.h"
#include "render/removal/selection_click_region.h"
#include "render/removal/selection_view_masks.h"

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

TEST(ClickRegion, NoDepthUnderTheClickIsAnEmptyRegionAndBadInputsThrow) {
  const Image photo = photo_with_square(0.9f, 0.3f, 10, 12, 30, 28);
  std::vector<float> depth(kW * kH, 0.0f);
  EXPECT_EQ(grow_click_region(photo, depth, 15, 20).area, 0u);
  EXPECT_THROW(grow_click_region(photo, depth, kW, 0), Error);
  EXPECT_THROW(grow_click_region(photo, std::vector<float>(10, 1.0f), 1, 1), Error);
}

TEST(MaskPhotoEdges, GrabCutMovesADisplacedSwollenMaskOntoThePhotosSquare) {
  // The photo: a bright square on a dark floor. The coverage: the square shifted by 3 px and swollen by
  // 2 px, fully covered in its middle - what a blurry run renders.
  const Image photo = photo_with_square(0.9f, 0.2f, 20, 20, 40, 40);
  Mask coarse(kW, kH);
  std::vector<float> coverage(kW * kH, 0.0f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool in = in_square(x, y, 21, 21, 45, 45);
      coarse.set(x, y, in);
      coverage[std::size_t(y) * kW + x] = in ? (in_square(x, y, 25, 25, 41, 41) ? 0.97f : 0.6f) : 0.05f;
    }
  const double before = iou_with_square(coarse, 20, 20, 40, 40);
  const Mask refined = refine_mask_with_photo(coarse, coverage, photo);
  const double after = iou_with_square(refined, 20, 20, 40, 40);
  EXPECT_LT(before, 0.72);
  EXPECT_GT(after, 0.9);  // 0.93: the cut keeps a pixel or two of the swollen side
  // An empty coverage mask stays empty; a photo of another size is an error.
  EXPECT_EQ(count_set(refine_mask_with_photo(Mask(kW, kH), coverage, photo)), 0u);
  EXPECT_THROW(refine_mask_with_photo(coarse, coverage, Image(8, 8, 3)), Error);
}

}  // namespace
}  // namespace goris
