// Where the fine-tune keeps the photo under the target's planar reflection
// (removal/lift/photo_under_reflection.h): a striped surface's photo within the texture's reach of the fill
// keeps its loss; a dark mirror image, the pixels the lighting-aware mask did not dereflect and a margin
// round the silhouette keep the fill; a plain surface keeps nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/util/error.h"
#include "removal/lift/photo_under_reflection.h"

namespace goris {
namespace {

constexpr int kW = 40, kH = 30;
constexpr std::size_t kN = std::size_t(kW) * kH;

Mask rect(int x0, int y0, int x1, int y1) {
  Mask m(kW, kH);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.set(x, y, true);
  return m;
}

// The fill: a flat 0.5 grey (a smooth fill's local mean). The photo: stripes of +-0.05 around it, and a dark
// blob (the target's mirror image, 0.3 below the fill) at x in [24, 30).
struct Scene {
  Mask reflection = rect(10, 5, 34, 25);   // the mirrored target on the surface
  Mask lighting = rect(10, 5, 30, 25);     // dereflected pixels: not the columns x >= 30
  Mask silhouette = rect(10, 0, 34, 5);    // the target itself, above the reflection
  Image fill{kW, kH, 3};
  std::vector<float> photo = std::vector<float>(3 * kN);
  Scene() {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const std::size_t p = std::size_t(y) * kW + x;
        const float stripe = (x / 2) % 2 ? 0.05f : -0.05f;
        const float v = x >= 24 && x < 30 ? 0.2f : 0.5f + stripe;
        for (std::size_t c = 0; c < 3; ++c) {
          fill.pixels[p * 3 + c] = 0.5f;
          photo[c * kN + p] = v;
        }
      }
  }
};

TEST(PhotoUnderReflection, TextureKeepsThePhotoAMirrorImageAndTheUndereflectedPixelsKeepTheFill) {
  Scene s;
  PhotoUnderReflectionSettings st;
  st.texture_multiple = 2.0, st.silhouette_margin = 3;
  std::size_t kept = 0;
  // Detail RMS 0.03: stripes of 0.05 are within 2 x 0.03 of the fill, the blob's 0.3 is not.
  const Mask left = reflection_left_to_the_fill(s.reflection, s.lighting, s.silhouette, s.photo, s.fill, 0.03, st, &kept);
  std::size_t expected = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool r = s.reflection(x, y);
      const bool keeps = r && x < 24 && y >= 5 + 3;  // striped, dereflected, beyond the margin
      expected += keeps;
      EXPECT_EQ(left(x, y), r && !keeps) << x << "," << y;
    }
  EXPECT_EQ(kept, expected);
  EXPECT_GT(kept, 0u);
}

TEST(PhotoUnderReflection, APlainSurfaceOrAnUnmeasuredOneKeepsTheFillEverywhere) {
  Scene s;
  for (double detail : {0.0, -1.0, 0.01}) {  // 2 x 0.01 is below the stripes' 0.05
    std::size_t kept = 7;
    const Mask left = reflection_left_to_the_fill(s.reflection, s.lighting, s.silhouette, s.photo, s.fill, detail, {}, &kept);
    EXPECT_EQ(left.data, s.reflection.data) << detail;
    EXPECT_EQ(kept, 0u) << detail;
  }
}

TEST(PhotoUnderReflection, TheMarginFollowsTheSilhouette) {
  Scene s;
  PhotoUnderReflectionSettings st;
  st.silhouette_margin = 0;
  const Mask left0 = reflection_left_to_the_fill(s.reflection, s.lighting, s.silhouette, s.photo, s.fill, 0.03, st);
  EXPECT_FALSE(left0(12, 5));  // next to the silhouette: kept without a margin
  st.silhouette_margin = 3;
  const Mask left3 = reflection_left_to_the_fill(s.reflection, s.lighting, s.silhouette, s.photo, s.fill, 0.03, st);
  EXPECT_TRUE(left3(12, 5));
  EXPECT_TRUE(left3(12, 7));
  EXPECT_FALSE(left3(12, 8));
}

TEST(PhotoUnderReflection, SizesThatDifferAreAnError) {
  Scene s;
  Image small(kW - 1, kH, 3);
  EXPECT_THROW(reflection_left_to_the_fill(s.reflection, s.lighting, s.silhouette, s.photo, small, 0.03), Error);
  std::vector<float> short_photo(3 * kN - 1);
  EXPECT_THROW(reflection_left_to_the_fill(s.reflection, s.lighting, s.silhouette, short_photo, s.fill, 0.03), Error);
  EXPECT_THROW(reflection_left_to_the_fill(s.reflection, rect(0, 0, 1, 1), Mask(kW, kH + 1), s.photo, s.fill, 0.03), Error);
}

}  // namespace
}  // namespace goris
