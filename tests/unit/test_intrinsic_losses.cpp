// Stage-1 intrinsic losses (normal prior, edge-aware smoothness, region, label BCE): values against direct
// definitions and gradients against central finite differences in double precision on small random images.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "tests/support/test_scenes.h"
#include "tests/support/test_support.h"
#include "train/losses/intrinsic_losses.h"

using namespace goris;
using goris::test::expect_gradient;
using goris::test::look_at;

namespace {

constexpr int W = 6, H = 5, HW = W * H;

std::vector<double> random_image(size_t n, std::mt19937_64& rng, double lo = 0.0, double hi = 1.0) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (auto& x : v) x = u(rng);
  return v;
}

// A mask with some zero pixels, some fractional.
std::vector<double> random_mask(std::mt19937_64& rng) {
  auto m = random_image(HW, rng);
  for (auto& v : m) v = v < 0.3 ? 0.0 : (v > 0.7 ? 1.0 : v);
  return m;
}


std::vector<double> unit_normals(std::mt19937_64& rng) {
  auto n = random_image(3 * HW, rng, -1.0, 1.0);
  for (int p = 0; p < HW; ++p) {
    const double l = std::sqrt(n[p] * n[p] + n[HW + p] * n[HW + p] + n[2 * HW + p] * n[2 * HW + p]);
    for (int c = 0; c < 3; ++c) n[c * HW + p] /= l;
  }
  return n;
}

}  // namespace

TEST(NormalPrior, ZeroForTheSameDirectionAtAnyLength) {
  std::mt19937_64 rng(3);
  const auto prior = unit_normals(rng);
  auto n = prior;
  for (int p = 0; p < HW; ++p)
    for (int c = 0; c < 3; ++c) n[c * HW + p] *= 0.2 + p;  // lengths differ, directions agree
  const std::vector<double> mask(HW, 1.0);
  EXPECT_NEAR(normal_prior_loss<double>(n.data(), prior.data(), mask.data(), W, H, nullptr), 0.0, 1e-12);
  // The opposite direction: |2u|_1 per pixel.
  for (auto& v : n) v = -v;
  double expect = 0;
  for (int i = 0; i < 3 * HW; ++i) expect += 2 * std::abs(prior[i]);
  EXPECT_NEAR(normal_prior_loss<double>(n.data(), prior.data(), mask.data(), W, H, nullptr), expect / HW, 1e-12);
}

TEST(NormalPrior, Gradient) {
  std::mt19937_64 rng(4);
  const auto prior = unit_normals(rng), mask = random_mask(rng);
  const auto n = random_image(3 * HW, rng, -1.0, 1.0);
  std::vector<double> g(3 * HW, 0.0);
  normal_prior_loss<double>(n.data(), prior.data(), mask.data(), W, H, g.data(), 0.5);
  expect_gradient([&](const auto& x) { return 0.5 * normal_prior_loss<double>(x.data(), prior.data(), mask.data(), W, H, nullptr); },
                  n, g);
}

TEST(EdgeAwareSmoothness, ConstantMapsCostNothingAndEdgesInThePhotoAreCheaper) {
  std::mt19937_64 rng(5);
  const std::vector<double> mask(HW, 1.0), flat_photo(3 * HW, 0.5);
  std::vector<double> x(HW, 0.3);
  EXPECT_EQ(edge_aware_smoothness<double>(x.data(), 1, flat_photo.data(), mask.data(), W, H, nullptr), 0.0);
  // A vertical step in x between columns 2 and 3: cost (H rows x 1 step) on a flat photo ...
  for (int y = 0; y < H; ++y)
    for (int c = 3; c < W; ++c) x[y * W + c] = 0.8;
  const double flat = edge_aware_smoothness<double>(x.data(), 1, flat_photo.data(), mask.data(), W, H, nullptr);
  EXPECT_NEAR(flat, H * 0.5 / HW, 1e-12);
  // ... and less where the photo has the same edge.
  auto photo = flat_photo;
  for (int ch = 0; ch < 3; ++ch)
    for (int y = 0; y < H; ++y)
      for (int c = 3; c < W; ++c) photo[ch * HW + y * W + c] = 1.0;
  const double edge = edge_aware_smoothness<double>(x.data(), 1, photo.data(), mask.data(), W, H, nullptr);
  EXPECT_NEAR(edge, flat * std::exp(-0.5), 1e-12);
  // Outside the mask: nothing.
  const std::vector<double> none(HW, 0.0);
  EXPECT_EQ(edge_aware_smoothness<double>(x.data(), 1, flat_photo.data(), none.data(), W, H, nullptr), 0.0);
}

TEST(EdgeAwareSmoothness, GradientPlainAndNormalised) {
  std::mt19937_64 rng(6);
  const auto photo = random_image(3 * HW, rng), mask = random_mask(rng);
  for (bool normalise : {false, true}) {
    const int C = 3;
    const auto x = random_image(C * HW, rng, -1.0, 1.0);
    std::vector<double> g(C * HW, 0.0);
    edge_aware_smoothness<double>(x.data(), C, photo.data(), mask.data(), W, H, g.data(), 0.05, normalise);
    expect_gradient([&](const auto& v) {
      return 0.05 * edge_aware_smoothness<double>(v.data(), C, photo.data(), mask.data(), W, H, nullptr, 1.0, normalise);
    }, x, g);
  }
}

TEST(RegionLoss, ValueAndGradient) {
  std::mt19937_64 rng(7);
  const auto m = random_image(HW, rng), gloss = random_mask(rng);
  double expect = 0;
  for (int p = 0; p < HW; ++p) expect += m[p] * gloss[p];
  std::vector<double> g(HW, 1.0);  // accumulates
  EXPECT_NEAR(region_loss<double>(m.data(), gloss.data(), W, H, g.data(), 2.0), expect / HW, 1e-14);
  for (int p = 0; p < HW; ++p) EXPECT_NEAR(g[p], 1.0 + 2.0 * gloss[p] / HW, 1e-14);
}

TEST(LabelBce, ValueGradientAndClamp) {
  std::mt19937_64 rng(8);
  const auto y = random_mask(rng);
  const auto l = random_image(HW, rng, 0.05, 0.95);
  double expect = 0;
  for (int p = 0; p < HW; ++p) expect -= y[p] * std::log(l[p]) + (1 - y[p]) * std::log(1 - l[p]);
  std::vector<double> g(HW, 0.0);
  EXPECT_NEAR(label_bce_loss<double>(l.data(), y.data(), W, H, g.data()), expect / HW, 1e-12);
  expect_gradient([&](const auto& x) { return label_bce_loss<double>(x.data(), y.data(), W, H, nullptr); }, l, g);
  // Saturated labels: finite loss, no gradient.
  std::vector<double> sat(HW, 1.0), gs(HW, 0.0);
  EXPECT_TRUE(std::isfinite(label_bce_loss<double>(sat.data(), y.data(), W, H, gs.data())));
  for (double v : gs) EXPECT_EQ(v, 0.0);
}
