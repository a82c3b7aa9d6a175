// Refilling a hole's part inside a region from that region alone: a table's pixels under a removed object
// take the table's colour, not the neighbouring object's.
#include <gtest/gtest.h>

#include "core/inpaint/harmonic_inpainter.h"
#include "core/inpaint/region_fill.h"
#include "core/util/error.h"

using namespace goris;

namespace {
constexpr int kW = 40, kH = 30;
// Left of x = 20 a grey table (0.2), right of it a red object; the hole straddles the edge.
Image table_and_object() {
  Image im(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      float* p = im.pixels.data() + (std::size_t(y) * kW + x) * 3;
      p[0] = x < 20 ? 0.2f : 0.9f, p[1] = p[2] = x < 20 ? 0.2f : 0.05f;
    }
  return im;
}
}  // namespace

TEST(RegionFill, TheRegionsPartOfTheHoleTakesOnlyTheRegionsColour) {
  const Image im = table_and_object();
  Mask hole(kW, kH);
  for (int y = 10; y < 20; ++y)
    for (int x = 12; x < 28; ++x) hole.set(x, y, true);
  std::vector<float> table(std::size_t(kW) * kH, 0.0f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 20; ++x) table[std::size_t(y) * kW + x] = 1.0f;
  const HarmonicInpainter harmonic;
  const MapInfo info{"v", "rgb", MapKind::Color};
  const Image plain = inpaint_map(harmonic, im, hole, info);
  const Image refilled = refill_inside_region(harmonic, im, plain, hole, table, info);
  const auto red = [](const Image& i, int x, int y) { return i.pixels.to_host()[(std::size_t(y) * kW + x) * 3]; };
  EXPECT_GT(red(plain, 18, 15), 0.3f) << "the plain fill drags the object's red onto the table";
  EXPECT_NEAR(red(refilled, 18, 15), 0.2f, 1e-3f);
  EXPECT_NEAR(red(refilled, 13, 11), 0.2f, 1e-3f);
  EXPECT_EQ(red(refilled, 25, 15), red(plain, 25, 15)) << "outside the region the plain fill stays";
  EXPECT_EQ(red(refilled, 5, 5), 0.2f) << "outside the hole nothing changes";
  // No source pixel inside the region (all of it in the hole): the plain fill is kept.
  std::vector<float> inside_hole(std::size_t(kW) * kH, 0.0f);
  inside_hole[std::size_t(15) * kW + 15] = 1.0f;
  EXPECT_EQ(refill_inside_region(harmonic, im, plain, hole, inside_hole, info).pixels.to_host(), plain.pixels.to_host());
  EXPECT_THROW(refill_inside_region(harmonic, im, plain, hole, std::vector<float>(3), info), Error);
}
