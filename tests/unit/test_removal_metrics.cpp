// LDR-FLIP ("FLIP: A Difference Evaluator for Alternating Images") and the changed-region removal metrics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/metrics/flip.h"
#include "core/metrics/removal_metrics.h"
#include "train/losses/image_losses.h"

namespace goris {
namespace {

// Planar [3][H][W] image.
struct Img {
  int w, h;
  std::vector<float> v;
  Img(int w_, int h_, float fill = 0.0f) : w(w_), h(h_), v(size_t(3) * w_ * h_, fill) {}
  float& at(int c, int x, int y) { return v[(size_t(c) * h + y) * w + x]; }
  const float* data() const { return v.data(); }
};

// A smooth colourful image plus uniform noise of +-`noise`, values in [0.35 - noise, 0.65 + noise].
Img textured(int w, int h, unsigned seed = 1, float noise = 0.05f) {
  Img img(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-noise, noise);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        img.at(c, x, y) = 0.5f + 0.15f * std::sin(0.2f * x + 1.3f * c) * std::cos(0.15f * y - 0.7f * c) + u(rng);
  return img;
}

double flip_of(const Img& test, const Img& ref, std::vector<float>* map = nullptr) {
  double mean = -1;
  std::vector<float> m = flip_error_map(test.data(), ref.data(), test.w, test.h, kFlipDefaultPpd, &mean);
  if (map) *map = std::move(m);
  return mean;
}

TEST(Flip, StandardViewingConditionIs67Ppd) { EXPECT_NEAR(flip_pixels_per_degree(), 67.02, 0.01); }

TEST(Flip, IdenticalImagesAreZero) {
  const Img a = textured(48, 40);
  std::vector<float> map;
  EXPECT_EQ(flip_of(a, a, &map), 0.0);
  ASSERT_EQ(map.size(), size_t(48 * 40));
  for (float e : map) EXPECT_EQ(e, 0.0f);
}

TEST(Flip, GrowsMonotonicallyWithNoiseAmplitude) {
  const Img ref = textured(64, 64);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> noise(ref.v.size());
  for (float& n : noise) n = u(rng);
  double previous = 0;
  for (float amplitude : {0.01f, 0.03f, 0.06f, 0.12f, 0.2f}) {  // ref +- 0.2 stays inside [0, 1]
    Img test = ref;
    for (size_t i = 0; i < noise.size(); ++i) test.v[i] += amplitude * noise[i];
    const double f = flip_of(test, ref);
    EXPECT_GT(f, previous) << "amplitude " << amplitude;
    EXPECT_LE(f, 1.0);
    previous = f;
  }
}

TEST(Flip, BlackVersusWhiteIsNearOne) {
  const Img black(32, 32, 0.0f), white(32, 32, 1.0f);
  std::vector<float> map;
  const double f = flip_of(black, white, &map);
  // Uniform images: no features, so E = Ec = the remapped HyAB(black, white)^0.7, about 0.97.
  EXPECT_GT(f, 0.95);
  EXPECT_LE(f, 1.0);
  for (float e : map) EXPECT_FLOAT_EQ(e, map[0]);
}

TEST(Flip, ErrorsStayInUnitRange) {
  Img a(40, 40), b(40, 40);
  std::mt19937 rng(3);
  std::bernoulli_distribution coin(0.5);
  for (size_t i = 0; i < a.v.size(); ++i) {  // black/white checkerboard noise against its inverse: worst case
    a.v[i] = coin(rng) ? 1.0f : 0.0f;
    b.v[i] = 1.0f - a.v[i];
  }
  std::vector<float> map;
  flip_of(a, b, &map);
  for (float e : map) {
    EXPECT_GE(e, 0.0f);
    EXPECT_LE(e, 1.0f);
  }
}

// LDR-FLIP treats the two images alike (same filters, absolute differences), so it is exactly symmetric.
TEST(Flip, IsExactlySymmetric) {
  const Img a = textured(50, 30, 1), b = textured(50, 30, 2);
  std::vector<float> ab, ba;
  flip_of(a, b, &ab);
  flip_of(b, a, &ba);
  ASSERT_EQ(ab.size(), ba.size());
  for (size_t i = 0; i < ab.size(); ++i) ASSERT_EQ(ab[i], ba[i]) << i;
  EXPECT_GT(flip_of(a, b), 0.0);
}

TEST(Flip, ShiftedEdgeErrsOnTheEdgeOnly) {
  const int w = 96, h = 32;
  Img ref(w, h), test(w, h);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        ref.at(c, x, y) = x < 48 ? 0.2f : 0.8f;
        test.at(c, x, y) = x < 49 ? 0.2f : 0.8f;  // the edge one pixel to the right
      }
  std::vector<float> map;
  flip_of(test, ref, &map);
  const float on_edge = map[size_t(h / 2) * w + 48];
  const float far = map[size_t(h / 2) * w + 5];  // beyond both filters' radii (10 and 9 pixels)
  EXPECT_GT(on_edge, 0.1f);
  EXPECT_EQ(far, 0.0f);
  EXPECT_GT(on_edge, map[size_t(h / 2) * w + 30]);
}

TEST(Flip, FireflyPeaksAtItsPixel) {
  const Img ref = textured(64, 64);
  Img test = ref;
  for (int c = 0; c < 3; ++c) test.at(c, 32, 32) = 1.0f;
  std::vector<float> map;
  flip_of(test, ref, &map);
  EXPECT_GT(map[32 * 64 + 32], 0.3f);
  EXPECT_GT(map[32 * 64 + 32], 10 * map[32 * 64 + 50]);
}

TEST(Flip, WeightedMean) {
  const Img a = textured(32, 32, 1), b = textured(32, 32, 2);
  double mean = 0;
  const std::vector<float> map = flip_error_map(a.data(), b.data(), 32, 32, kFlipDefaultPpd, &mean);
  EXPECT_NEAR(flip_mean(a.data(), b.data(), 32, 32), mean, 1e-12);
  std::vector<float> weight(32 * 32, 0.0f);
  EXPECT_TRUE(std::isnan(flip_pooled_mean(map, weight.data())));
  weight[5] = 2.0f;
  weight[700] = 1.0f;
  EXPECT_NEAR(flip_pooled_mean(map, weight.data()), (2.0 * map[5] + map[700]) / 3.0, 1e-7);
  EXPECT_THROW(flip_error_map(nullptr, b.data(), 32, 32), std::invalid_argument);
}

// --- changed region and removal metrics ---------------------------------------------------------------

constexpr int kW = 64, kH = 64;
// Background noise small enough that a median window's rank shift (an outlier entering it) stays under the
// 0.04 threshold; with stronger texture the median itself moves by more than that next to the target.
constexpr float kSceneNoise = 0.01f;
constexpr int kX0 = 20, kY0 = 24, kSide = 12;  // the target: a square [kX0, kX0 + kSide) x [kY0, kY0 + kSide)

// after: the scene without the target; before: the same with a red square in it.
void scene(Img& after, Img& before) {
  after = textured(kW, kH, 5, kSceneNoise);
  before = after;
  for (int y = kY0; y < kY0 + kSide; ++y)
    for (int x = kX0; x < kX0 + kSide; ++x) {
      before.at(0, x, y) = 0.9f;
      before.at(1, x, y) = 0.1f;
      before.at(2, x, y) = 0.1f;
    }
}

// Chebyshev distance from (x, y) to the square.
int square_distance(int x, int y) {
  const int dx = std::max({kX0 - x, 0, x - (kX0 + kSide - 1)});
  const int dy = std::max({kY0 - y, 0, y - (kY0 + kSide - 1)});
  return std::max(dx, dy);
}

TEST(ChangedRegion, CoversTheSquarePlusDilationAndNothingElse) {
  Img after(1, 1), before(1, 1);
  scene(after, before);
  const ChangedRegionOptions options;  // threshold 0.04, median 3, dilate 2
  const ChangedRegion region = changed_region(before.data(), after.data(), kW, kH, options);
  ASSERT_EQ(region.mask.size(), size_t(kW * kH));
  size_t count = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int d = square_distance(x, y);
      const bool in = region.mask[size_t(y) * kW + x] != 0;
      count += in;
      if (d <= 1) {  // the square and a ring within the dilation
        EXPECT_TRUE(in) << x << "," << y;
      } else if (d > options.dilate) {
        EXPECT_FALSE(in) << x << "," << y;
      }
    }
  EXPECT_DOUBLE_EQ(region.fraction, double(count) / (kW * kH));
  // The median erodes the square's 4 corner pixels, so the dilated square loses its 4 outer corners.
  const int dilated = (kSide + 2 * options.dilate) * (kSide + 2 * options.dilate);
  EXPECT_EQ(count, size_t(dilated - 4));
}

TEST(ChangedRegion, NoDilationGivesTheSquare) {
  Img after(1, 1), before(1, 1);
  scene(after, before);
  ChangedRegionOptions options;
  options.dilate = 0;
  options.median = 1;
  const ChangedRegion region = changed_region(before.data(), after.data(), kW, kH, options);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) EXPECT_EQ(region.mask[size_t(y) * kW + x], square_distance(x, y) == 0 ? 1 : 0);
  EXPECT_DOUBLE_EQ(region.fraction, double(kSide * kSide) / (kW * kH));
}

TEST(ChangedRegion, SaltNoiseIsNoChange) {
  const Img after = textured(kW, kH, 9, kSceneNoise);
  Img before = after;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> cell(0, 15);
  for (int gy = 0; gy < kH / 4; ++gy)  // isolated single pixels: at most one per 4x4 cell, one cell in two
    for (int gx = 0; gx < kW / 4; ++gx)
      if ((gx + gy) % 2 == 0) {
        const int x = gx * 4 + cell(rng) % 3, y = gy * 4 + cell(rng) % 3;
        for (int c = 0; c < 3; ++c) before.at(c, x, y) = cell(rng) % 2 ? 1.0f : 0.0f;
      }
  const ChangedRegion region = changed_region(before.data(), after.data(), kW, kH);
  EXPECT_EQ(region.fraction, 0.0);
  // Without the median the same noise is a change.
  ChangedRegionOptions no_median;
  no_median.median = 1;
  EXPECT_GT(changed_region(before.data(), after.data(), kW, kH, no_median).fraction, 0.1);
}

TEST(RemovalMetrics, GhostRatio) {
  Img after(1, 1), before(1, 1);
  scene(after, before);
  EXPECT_NEAR(removal_metrics(before.data(), after.data(), before.data(), kW, kH).ghost_ratio, 1.0, 1e-12);
  EXPECT_NEAR(removal_metrics(after.data(), after.data(), before.data(), kW, kH).ghost_ratio, 0.0, 1e-12);
  Img half = after;
  for (size_t i = 0; i < half.v.size(); ++i) half.v[i] = 0.5f * (after.v[i] + before.v[i]);
  EXPECT_NEAR(removal_metrics(half.data(), after.data(), before.data(), kW, kH).ghost_ratio, 0.5, 0.02);  // the median is not linear: about half
}

TEST(RemovalMetrics, GroundTruthNoiseIsNoGhost) {
  // A clean render of the scene without the object against a ground truth with salt noise: no ghost.
  Img clean(1, 1), before(1, 1);
  scene(clean, before);
  Img noisy = clean;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> cell(0, 3);
  for (int gy = 0; gy < kH / 4; ++gy)
    for (int gx = 0; gx < kW / 4; ++gx)
      for (int c = 0; c < 3; ++c) noisy.at(c, gx * 4 + cell(rng) % 3, gy * 4 + cell(rng) % 3) = 1.0f;
  const RemovalMetrics m = removal_metrics(clean.data(), noisy.data(), before.data(), kW, kH);
  EXPECT_LT(m.ghost_ratio, 0.02);
  EXPECT_GT(m.ghost_imprint, 0.0);
  EXPECT_NEAR(m.ghost_ratio, m.ghost_residual / m.ghost_imprint, 1e-12);
  // Leaving the object in is still a full ghost.
  EXPECT_GT(removal_metrics(before.data(), noisy.data(), before.data(), kW, kH).ghost_ratio, 0.95);
}

TEST(RemovalMetrics, PerfectRemoval) {
  Img after(1, 1), before(1, 1);
  scene(after, before);
  const RemovalMetrics m = removal_metrics(after.data(), after.data(), before.data(), kW, kH);
  EXPECT_GT(m.region_fraction, 0.0);
  EXPECT_TRUE(std::isinf(m.region_psnr) && m.region_psnr > 0);
  EXPECT_NEAR(m.region_ssim, 1.0, 1e-6);
  EXPECT_EQ(m.flip, 0.0);
  EXPECT_EQ(m.region_flip, 0.0);
  EXPECT_EQ(m.ghost_ratio, 0.0);
}

TEST(RemovalMetrics, UnremovedTargetScoresWorseInsideTheRegion) {
  Img after(1, 1), before(1, 1);
  scene(after, before);
  const RemovalMetrics m = removal_metrics(before.data(), after.data(), before.data(), kW, kH);
  EXPECT_LT(m.region_psnr, 20.0);
  EXPECT_LT(m.region_ssim, 0.9);
  EXPECT_GT(m.region_flip, m.flip);  // the whole-image mean is diluted by the untouched background
  EXPECT_GT(m.flip, 0.0);
  // Region PSNR from its definition.
  double se = 0;
  size_t count = 0;
  const size_t n = size_t(kW) * kH;
  for (size_t p = 0; p < n; ++p)
    if (m.region[p]) {
      ++count;
      for (int c = 0; c < 3; ++c) se += std::pow(double(before.v[c * n + p]) - after.v[c * n + p], 2);
    }
  EXPECT_NEAR(m.region_psnr, 10 * std::log10(3.0 * count / se), 1e-9);
}

// The ghost's two sums are region residuals, and a third image (a model's render with the target) measures
// against `before` in the same units: half the imprint away from it is a floor of one half.
TEST(RegionResidual, IsTheGhostsSumAndMeasuresAFloor) {
  Img after(1, 1), before(1, 1);
  scene(after, before);
  Img half = after;
  for (size_t i = 0; i < half.v.size(); ++i) half.v[i] = 0.5f * (after.v[i] + before.v[i]);
  const RemovalMetrics m = removal_metrics(half.data(), after.data(), before.data(), kW, kH);
  EXPECT_DOUBLE_EQ(region_residual(half.data(), after.data(), m.region, kW, kH), m.ghost_residual);
  EXPECT_DOUBLE_EQ(region_residual(before.data(), after.data(), m.region, kW, kH), m.ghost_imprint);
  EXPECT_NEAR(region_residual(half.data(), before.data(), m.region, kW, kH) / m.ghost_imprint, 0.5, 0.02);
  EXPECT_EQ(region_residual(before.data(), before.data(), m.region, kW, kH), 0.0);
  // Without the median: the plain sum over the region's pixels and channels.
  double direct = 0;
  const size_t n = size_t(kW) * kH;
  for (size_t p = 0; p < n; ++p)
    if (m.region[p])
      for (int c = 0; c < 3; ++c) direct += std::abs(double(half.v[c * n + p]) - before.v[c * n + p]);
  EXPECT_NEAR(region_residual(half.data(), before.data(), m.region, kW, kH, 1), direct, 1e-9 * direct);
  // Pixels outside the region never count.
  Img far = before;
  far.at(1, 2, 2) = 1.0f - far.at(1, 2, 2);
  ASSERT_EQ(m.region[2 * kW + 2], 0);
  EXPECT_EQ(region_residual(far.data(), before.data(), m.region, kW, kH, 1), 0.0);
  EXPECT_THROW(region_residual(half.data(), before.data(), std::vector<uint8_t>(7), kW, kH), std::invalid_argument);
}

TEST(RemovalMetrics, EmptyRegionIsNaN) {
  const Img after = textured(kW, kH, 5);
  const Img render = textured(kW, kH, 6);
  const RemovalMetrics m = removal_metrics(render.data(), after.data(), after.data(), kW, kH);
  EXPECT_EQ(m.region_fraction, 0.0);
  EXPECT_TRUE(std::isnan(m.region_psnr));
  EXPECT_TRUE(std::isnan(m.region_ssim));
  EXPECT_TRUE(std::isnan(m.ghost_ratio));
  EXPECT_TRUE(std::isnan(m.region_flip));
  EXPECT_GT(m.flip, 0.0);  // the whole-image FLIP is still defined
}

// The SSIM map's mean is the repository's training SSIM (same window, constants and zero padding).
TEST(SsimMap, MeanMatchesTrainingSsim) {
  const Img a = textured(40, 36, 1), b = textured(40, 36, 2);
  const std::vector<float> map = ssim_map(a.data(), b.data(), 40, 36, 3);
  double mean = 0;
  for (float v : map) mean += v;
  mean /= double(map.size());
  EXPECT_NEAR(mean, ssim<double>(std::vector<double>(a.v.begin(), a.v.end()).data(),
                                 std::vector<double>(b.v.begin(), b.v.end()).data(), 3, 40, 36),
              1e-6);
  const std::vector<float> same = ssim_map(a.data(), a.data(), 40, 36, 3);
  for (float v : same) EXPECT_NEAR(v, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace goris
