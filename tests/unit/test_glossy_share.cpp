// The share of the glossy surface's colour in the traced glossy term (train/intrinsic/glossy_share.h).
#include <gtest/gtest.h>

#include <vector>

#include "core/util/error.h"
#include "train/intrinsic/glossy_share.h"

using namespace goris;

namespace {
// A 2x2 view, planar RGB: colour C and SH colour D per pixel (the same in every channel).
std::vector<float> planar(const std::vector<float>& grey) {
  std::vector<float> out;
  for (int c = 0; c < 3; ++c) out.insert(out.end(), grey.begin(), grey.end());
  return out;
}
}  // namespace

TEST(GlossyShare, IsTheGlossyTermsPartOfTheColourOnGlossyPixelsOnly) {
  GlossyShare s;
  EXPECT_FALSE(s.share().has_value());  // nothing measured
  // Pixels 0 and 1 glossy: C 0.5 = D 0.2 + G 0.3 and C 0.3 = D 0.3 (no reflection); pixels 2 and 3 not glossy,
  // their colour all in G, which must not count.
  add_glossy_share(planar({0.5f, 0.3f, 0.9f, 0.9f}), planar({0.2f, 0.3f, 0.0f, 0.0f}), {1.0f, 0.5f, 0.49f, 0.0f}, s);
  EXPECT_EQ(s.pixels, 2u);
  EXPECT_EQ(s.views, 1u);
  ASSERT_TRUE(s.share().has_value());
  EXPECT_NEAR(*s.share(), 0.3 / 0.8, 1e-6);
  // A second view, all of whose glossy colour is in D (a mirror world): pooled over the pixels.
  add_glossy_share(planar({0.4f, 0.0f, 0.0f, 0.0f}), planar({0.4f, 0.0f, 0.0f, 0.0f}), {1.0f, 0.0f, 0.0f, 0.0f}, s);
  EXPECT_EQ(s.pixels, 3u);
  EXPECT_EQ(s.views, 2u);
  EXPECT_NEAR(*s.share(), 0.3 / 1.2, 1e-6);
  // A view without glossy pixels adds nothing.
  add_glossy_share(planar({1, 1, 1, 1}), planar({0, 0, 0, 0}), {0, 0, 0, 0}, s);
  EXPECT_EQ(s.views, 2u);
  EXPECT_NEAR(*s.share(), 0.3 / 1.2, 1e-6);
}

TEST(GlossyShare, BlackGlossyPixelsHaveNoShare) {
  GlossyShare s;
  add_glossy_share(planar({0, 0, 0, 0}), planar({0, 0, 0, 0}), {1, 1, 1, 1}, s);
  EXPECT_EQ(s.pixels, 4u);
  EXPECT_FALSE(s.share().has_value());
}

TEST(GlossyShare, SizesMustAgree) {
  GlossyShare s;
  EXPECT_THROW(add_glossy_share(std::vector<float>(12), std::vector<float>(9), std::vector<float>(4), s), Error);
  EXPECT_THROW(add_glossy_share(std::vector<float>(12), std::vector<float>(12), std::vector<float>(3), s), Error);
}
