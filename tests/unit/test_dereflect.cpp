// The fine-tune's targets inside the lighting-aware mask (removal/lift/dereflect.h): the photo minus what
// stage 1 says the target added, only on the mask's pixels, clamped to the photo's range.
#include <gtest/gtest.h>

#include <vector>

#include "core/util/error.h"
#include "removal/lift/dereflect.h"

using namespace goris;

namespace {

// Planar [3][H][W] with channel c of pixel p = base + 0.1 c + 0.01 p.
std::vector<float> ramp(int w, int h, float base) {
  const std::size_t hw = std::size_t(w) * h;
  std::vector<float> v(3 * hw);
  for (int c = 0; c < 3; ++c)
    for (std::size_t p = 0; p < hw; ++p) v[c * hw + p] = base + 0.1f * c + 0.01f * float(p);
  return v;
}

}  // namespace

TEST(Dereflect, SubtractsTheTargetsShareOnlyInsideTheMask) {
  const int w = 4, h = 3;
  const std::size_t hw = std::size_t(w) * h;
  std::vector<float> photo = ramp(w, h, 0.3f);
  const std::vector<float> original = photo;
  std::vector<float> with = ramp(w, h, 0.2f), removed = ramp(w, h, 0.2f);
  Mask m(w, h);
  m.set(1, 0, true);
  m.set(2, 2, true);
  // Pixel (1, 0): the target added a bright reflection (+0.25 in red, +0.05 in green); pixel (2, 2): the
  // target hid light (removing it brightens blue by 0.1); pixel (3, 1), outside the mask, changes too.
  with[0 * hw + 1] += 0.25f;
  with[1 * hw + 1] += 0.05f;
  removed[2 * hw + 10] += 0.1f;
  with[0 * hw + 7] += 0.5f;
  const double change = subtract_reflection(photo, with, removed, m);
  for (int c = 0; c < 3; ++c)
    for (std::size_t p = 0; p < hw; ++p) {
      float expect = original[c * hw + p];
      if (p == 1 && c == 0) expect -= 0.25f;
      if (p == 1 && c == 1) expect -= 0.05f;
      if (p == 10 && c == 2) expect += 0.1f;
      EXPECT_NEAR(photo[c * hw + p], expect, 1e-6f) << "channel " << c << " pixel " << p;
    }
  EXPECT_NEAR(change, (0.25 + 0.05) / 3 + 0.1 / 3, 1e-6);
}

TEST(Dereflect, ClampsToThePhotosRange) {
  const int w = 2, h = 1;
  std::vector<float> photo = {0.1f, 0.9f, 0.1f, 0.9f, 0.1f, 0.9f};
  const std::vector<float> with = {0.6f, 0.0f, 0.6f, 0.0f, 0.6f, 0.0f};
  const std::vector<float> removed = {0.0f, 0.5f, 0.0f, 0.5f, 0.0f, 0.5f};
  Mask m(w, h, 255);
  const double change = subtract_reflection(photo, with, removed, m);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(photo[c * 2 + 0], 0.0f);  // 0.1 - 0.6 clamps at 0: the change is only 0.1
    EXPECT_FLOAT_EQ(photo[c * 2 + 1], 1.0f);  // 0.9 + 0.5 clamps at 1
  }
  EXPECT_NEAR(change, 0.1 + 0.1, 1e-6);
}

TEST(Dereflect, SizesThatDifferAreAnError) {
  std::vector<float> photo(3 * 6, 0.5f);
  const std::vector<float> with(3 * 6, 0.5f), removed(3 * 5, 0.5f);
  const Mask m(3, 2, 255);
  EXPECT_THROW(subtract_reflection(photo, with, removed, m), Error);
  const Mask wrong(2, 2, 255);
  EXPECT_THROW(subtract_reflection(photo, with, with, wrong), Error);
}
