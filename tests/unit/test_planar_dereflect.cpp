// The target's planar reflection taken out of a photo by a fitted scale and blur of its mirror image:
// the fit finds the scale and the blur a photo was made with, subtracts only inside the region, keeps the
// surface's own texture, and leaves a photo whose residual the mirror image does not explain as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/util/error.h"
#include "removal/masks/planar_dereflect.h"

using namespace goris;

namespace {
constexpr int kW = 48, kH = 32;
constexpr std::size_t kHW = std::size_t(kW) * kH;

// A bright disc (the target's mirror image, less what it hid) on black, planar RGB.
std::vector<float> disc(float cx, float cy, float r, float value) {
  std::vector<float> d(3 * kHW, 0.0f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
        for (int c = 0; c < 3; ++c) d[c * kHW + std::size_t(y) * kW + x] = value * (0.6f + 0.2f * float(c));
  return d;
}

Mask box(int x0, int y0, int x1, int y1) {
  Mask m(kW, kH);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.set(x, y, true);
  return m;
}

// A veined surface: stripes the smooth fill cannot know.
std::vector<float> veined_surface() {
  std::vector<float> s(3 * kHW);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        s[c * kHW + std::size_t(y) * kW + x] = 0.5f + 0.08f * std::sin(0.9f * float(x) + 0.3f * float(y));
  return s;
}
}  // namespace

TEST(PlanarDereflect, FindsTheScaleAndBlurAndKeepsTheTexture) {
  const std::vector<float> surface = veined_surface();
  const std::vector<float> delta = disc(24, 16, 6, 0.8f);
  PlanarDereflectSettings settings;
  const float sigma = settings.blur_fractions[2] * kW;
  const std::vector<float> blurred = gaussian_blur_planar(delta, 3, kW, kH, sigma);
  std::vector<float> photo(3 * kHW);
  for (std::size_t k = 0; k < photo.size(); ++k) photo[k] = surface[k] + 0.4f * blurred[k];
  const std::vector<float> smooth(3 * kHW, 0.5f);  // what a smooth fill knows of the surface
  const Mask region = box(12, 4, 36, 28);
  std::vector<float> out = photo;
  const PlanarDereflectFit fit = dereflect_planar_reflection(out, smooth, delta, region, settings);
  ASSERT_TRUE(fit.applied);
  EXPECT_NEAR(fit.reflectance, 0.4f, 0.03f);
  EXPECT_FLOAT_EQ(fit.blur, sigma);
  EXPECT_GT(fit.explained, 0.7f);  // the veins are the rest
  EXPECT_EQ(fit.pixels, count_set(region));
  double err_before = 0, err_after = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::size_t k = c * kHW + std::size_t(y) * kW + x;
        if (region(x, y)) {
          err_before += std::abs(photo[k] - surface[k]);
          err_after += std::abs(out[k] - surface[k]);
        } else {
          EXPECT_EQ(out[k], photo[k]);  // nothing changes outside the region
        }
      }
  EXPECT_LT(err_after, 0.1 * err_before);  // the veins stay, the reflection goes
}

TEST(PlanarDereflect, LeavesAPhotoTheMirrorImageDoesNotExplain) {
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  std::vector<float> photo(3 * kHW);
  for (float& v : photo) v = 0.5f + noise(rng);
  const std::vector<float> smooth(3 * kHW, 0.5f);
  const std::vector<float> delta = disc(24, 16, 6, 0.8f);
  std::vector<float> out = photo;
  const PlanarDereflectFit fit = dereflect_planar_reflection(out, smooth, delta, box(12, 4, 36, 28));
  EXPECT_FALSE(fit.applied);
  EXPECT_LT(fit.explained, 0.1f);
  EXPECT_EQ(out, photo);
  // With no region or no mirror image nothing is fitted.
  EXPECT_FALSE(dereflect_planar_reflection(out, smooth, delta, Mask(kW, kH)).applied);
  EXPECT_FALSE(dereflect_planar_reflection(out, smooth, std::vector<float>(3 * kHW, 0.0f), box(12, 4, 36, 28)).applied);
  EXPECT_EQ(out, photo);
}

TEST(PlanarDereflect, SizesThatDifferAreAnError) {
  std::vector<float> photo(3 * kHW, 0.5f);
  const std::vector<float> smooth(3 * kHW, 0.5f);
  EXPECT_THROW(dereflect_planar_reflection(photo, smooth, std::vector<float>(kHW), box(0, 0, 4, 4)), Error);
  EXPECT_THROW(gaussian_blur_planar(std::vector<float>(5), 3, kW, kH, 1.0f), Error);
}
