// Image losses: values against direct definitions and gradients against central finite differences, in
// double precision on small random images.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "tests/support/test_scenes.h"
#include "tests/support/test_support.h"
#include "train/losses/depth_normal_loss.h"
#include "train/losses/image_losses.h"

using namespace goris;
using goris::test::expect_gradient;
using goris::test::look_at;

namespace {

std::vector<double> random_image(size_t n, std::mt19937_64& rng, double lo = 0.0, double hi = 1.0) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (auto& x : v) x = u(rng);
  return v;
}


}  // namespace

TEST(L1Loss, ValueAndGradient) {
  std::mt19937_64 rng(1);
  const size_t n = 3 * 7 * 5;
  const auto t = random_image(n, rng);
  auto p = random_image(n, rng);
  for (size_t i = 0; i < n; ++i)  // keep every |p - t| away from the kink at 0
    if (std::abs(p[i] - t[i]) < 1e-3) p[i] += 2e-3;
  double expect = 0;
  for (size_t i = 0; i < n; ++i) expect += std::abs(p[i] - t[i]);
  std::vector<double> g(n, 0.0);
  EXPECT_NEAR(l1_loss<double>(p.data(), t.data(), n, g.data(), 0.7), expect / n, 1e-14);
  auto f = [&](const std::vector<double>& x) { return 0.7 * l1_loss<double>(x.data(), t.data(), n); };
  expect_gradient(f, p, g, 1e-6, 1e-7);
}

TEST(L1Loss, PerElementWeightsValueAndGradient) {
  // The alpha loss in stage 2: pixels of weight 0 neither count nor get a gradient.
  std::mt19937_64 rng(2);
  const size_t n = 6 * 5;
  const auto t = random_image(n, rng);
  auto p = random_image(n, rng);
  const auto w = random_image(n, rng);
  for (size_t i = 0; i < n; ++i)
    if (std::abs(p[i] - t[i]) < 1e-3) p[i] += 2e-3;
  std::vector<double> weights(w);
  weights[3] = 0.0;
  double expect = 0;
  for (size_t i = 0; i < n; ++i) expect += weights[i] * std::abs(p[i] - t[i]);
  std::vector<double> g(n, 0.0);
  EXPECT_NEAR(l1_loss<double>(p.data(), t.data(), n, g.data(), 0.7, weights.data()), expect / n, 1e-14);
  EXPECT_EQ(g[3], 0.0);
  auto f = [&](const std::vector<double>& x) { return 0.7 * l1_loss<double>(x.data(), t.data(), n, nullptr, 1.0, weights.data()); };
  expect_gradient(f, p, g, 1e-6, 1e-7);
}

TEST(L1Loss, GradientAccumulates) {
  std::vector<double> p = {0.5, 0.2}, t = {0.1, 0.4}, g = {1.0, 1.0};
  l1_loss<double>(p.data(), t.data(), 2, g.data());
  EXPECT_DOUBLE_EQ(g[0], 1.5);
  EXPECT_DOUBLE_EQ(g[1], 0.5);
}

TEST(Ssim, IdenticalImagesGiveOne) {
  std::mt19937_64 rng(2);
  const auto a = random_image(3 * 20 * 17, rng);
  EXPECT_NEAR(ssim<double>(a.data(), a.data(), 3, 20, 17), 1.0, 1e-12);
  std::vector<float> af(a.begin(), a.end());
  EXPECT_NEAR(ssim<float>(af.data(), af.data(), 3, 20, 17), 1.0f, 1e-5f);
}

TEST(Ssim, MatchesDirectWindowedDefinition) {
  // A direct 2D (non-separable) evaluation of the same definition at every pixel.
  std::mt19937_64 rng(3);
  const int w = 14, h = 12;
  const auto x = random_image(w * h, rng), y = random_image(w * h, rng);
  double g1[11], gs = 0;
  for (int i = 0; i < 11; ++i) gs += g1[i] = std::exp(-(i - 5) * (i - 5) / (2 * 1.5 * 1.5));
  for (double& v : g1) v /= gs;
  double total = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      double m1 = 0, m2 = 0, s11 = 0, s22 = 0, s12 = 0;
      for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
          const int qx = px + dx, qy = py + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const double wgt = g1[dx + 5] * g1[dy + 5], a = x[qy * w + qx], b = y[qy * w + qx];
          m1 += wgt * a;
          m2 += wgt * b;
          s11 += wgt * a * a;
          s22 += wgt * b * b;
          s12 += wgt * a * b;
        }
      const double C1 = 1e-4, C2 = 9e-4;
      total += ((2 * m1 * m2 + C1) * (2 * (s12 - m1 * m2) + C2)) /
               ((m1 * m1 + m2 * m2 + C1) * ((s11 - m1 * m1) + (s22 - m2 * m2) + C2));
    }
  EXPECT_NEAR(ssim<double>(x.data(), y.data(), 1, w, h), total / (w * h), 1e-13);
}

TEST(Ssim, GradientMatchesFiniteDifferences) {
  std::mt19937_64 rng(4);
  const int c = 2, w = 13, h = 9;
  const size_t n = size_t(c) * w * h;
  const auto t = random_image(n, rng);
  auto p = t;  // a nearby prediction: the SSIM gradient is informative there
  for (auto& v : p) v += std::uniform_real_distribution<double>(-0.2, 0.2)(rng);
  std::vector<double> g(n, 0.0);
  ssim<double>(p.data(), t.data(), c, w, h, g.data(), -0.3);
  auto f = [&](const std::vector<double>& x) { return -0.3 * ssim<double>(x.data(), t.data(), c, w, h); };
  expect_gradient(f, p, g, 1e-6, 1e-6);
}

TEST(ColorLoss, CombinesL1AndSsim) {
  std::mt19937_64 rng(5);
  const int c = 3, w = 11, h = 10;
  const size_t n = size_t(c) * w * h;
  const auto t = random_image(n, rng), p = random_image(n, rng);
  std::vector<double> g(n, 0.0);
  const ColorLossParts parts = color_loss<double>(p.data(), t.data(), c, w, h, g.data());
  EXPECT_NEAR(parts.l1, l1_loss<double>(p.data(), t.data(), n), 1e-14);
  EXPECT_NEAR(parts.ssim, ssim<double>(p.data(), t.data(), c, w, h), 1e-14);
  EXPECT_NEAR(parts.total, 0.8 * parts.l1 + 0.2 * (1 - parts.ssim), 1e-14);
  auto f = [&](const std::vector<double>& x) { return color_loss<double>(x.data(), t.data(), c, w, h).total; };
  expect_gradient(f, p, g, 1e-7, 1e-6);
}

TEST(Psnr, FromMse) {
  EXPECT_NEAR(psnr_from_mse(1e-3), 30.0, 1e-12);
  EXPECT_TRUE(std::isinf(psnr_from_mse(0.0)));
  std::vector<float> a = {0.0f, 0.5f}, b = {0.1f, 0.5f};
  EXPECT_NEAR(mse<float>(a.data(), b.data(), 2), 0.005f, 1e-7f);
}

namespace {
struct DepthScene {
  int w = 9, h = 8;
  double fx = 11, fy = 10, cx = 4.3, cy = 3.9;
  std::vector<double> depth, normal, weight;
};
DepthScene random_depth_scene(std::mt19937_64& rng) {
  DepthScene s;
  const size_t hw = size_t(s.w) * s.h;
  std::uniform_real_distribution<double> u(-1, 1);
  s.depth.resize(hw);
  for (int y = 0; y < s.h; ++y)  // a tilted plane plus noise: well-defined normals everywhere
    for (int x = 0; x < s.w; ++x) s.depth[y * s.w + x] = 3.0 + 0.05 * x - 0.03 * y + 0.05 * u(rng);
  s.normal.resize(3 * hw);
  for (size_t p = 0; p < hw; ++p) {
    s.normal[p] = 0.3 * u(rng);
    s.normal[hw + p] = 0.3 * u(rng);
    s.normal[2 * hw + p] = -0.8 + 0.1 * u(rng);
  }
  s.weight = random_image(hw, rng, 0.2, 1.0);
  return s;
}
}  // namespace

TEST(DepthNormalLoss, PlaneFacingTheCameraIsConsistent) {
  // A fronto-parallel plane: the depth normal is (0, 0, -1); a rendered normal along it costs nothing.
  const int w = 6, h = 5;
  std::vector<double> depth(w * h, 2.0), normal(3 * w * h, 0.0), nd(3 * w * h);
  for (int p = 0; p < w * h; ++p) normal[2 * w * h + p] = -0.7;  // any length
  EXPECT_NEAR(depth_normal_loss<double>(depth.data(), normal.data(), nullptr, w, h, 5, 5, 3, 2.5), 0.0, 1e-14);
  normal_from_depth<double>(depth.data(), w, h, 5, 5, 3, 2.5, nd.data());
  const int p = 2 * w + 2;
  EXPECT_NEAR(nd[2 * w * h + p], -1.0, 1e-14);
  // The opposite normal costs 2 per interior pixel.
  for (int q = 0; q < w * h; ++q) normal[2 * w * h + q] = 1.0;
  EXPECT_NEAR(depth_normal_loss<double>(depth.data(), normal.data(), nullptr, w, h, 5, 5, 3, 2.5), 2.0, 1e-14);
}

TEST(DepthNormalLoss, GradientsMatchFiniteDifferences) {
  std::mt19937_64 rng(6);
  DepthScene s = random_depth_scene(rng);
  const size_t hw = size_t(s.w) * s.h;
  std::vector<double> gd(hw, 0.0), gn(3 * hw, 0.0);
  depth_normal_loss<double>(s.depth.data(), s.normal.data(), s.weight.data(), s.w, s.h, s.fx, s.fy, s.cx, s.cy,
                            gd.data(), gn.data(), 0.5);
  auto f_depth = [&](const std::vector<double>& d) {
    return depth_normal_loss<double>(d.data(), s.normal.data(), s.weight.data(), s.w, s.h, s.fx, s.fy, s.cx, s.cy,
                                     nullptr, nullptr, 0.5) * 0.5;
  };
  expect_gradient(f_depth, s.depth, gd, 1e-6, 1e-6);
  auto f_normal = [&](const std::vector<double>& n) {
    return depth_normal_loss<double>(s.depth.data(), n.data(), s.weight.data(), s.w, s.h, s.fx, s.fy, s.cx, s.cy) *
           0.5;
  };
  expect_gradient(f_normal, s.normal, gn, 1e-6, 1e-6);
}

TEST(DepthNormalLoss, ZeroWeightPixelsAreIgnored) {
  std::mt19937_64 rng(7);
  DepthScene s = random_depth_scene(rng);
  const size_t hw = size_t(s.w) * s.h;
  std::vector<double> zero(hw, 0.0), gd(hw, 0.0), gn(3 * hw, 0.0);
  EXPECT_EQ(depth_normal_loss<double>(s.depth.data(), s.normal.data(), zero.data(), s.w, s.h, s.fx, s.fy, s.cx, s.cy,
                                      gd.data(), gn.data()),
            0.0);
  for (double v : gd) EXPECT_EQ(v, 0.0);
  for (double v : gn) EXPECT_EQ(v, 0.0);
}

TEST(DepthNormalLoss, RenderedFormGradientsMatchFiniteDifferences) {
  // Expected depth = weighted depth / alpha: the gradient reaches the alpha through the division, and the
  // median-depth term its own input; pixels at the alpha clamp take the clamped branch.
  std::mt19937_64 rng(8);
  DepthScene s = random_depth_scene(rng);
  const size_t hw = size_t(s.w) * s.h;
  std::vector<double> alpha = random_image(hw, rng, 0.3, 1.0);
  alpha[3] = 1e-6;  // below the clamp
  std::vector<double> weighted(hw), median(hw);
  for (size_t p = 0; p < hw; ++p) {
    weighted[p] = s.depth[p] * alpha[p];
    median[p] = s.depth[p] + 0.02 * std::sin(double(p));
  }
  weighted[3] = s.depth[3] * 1e-4;  // a sane expected depth at the clamped pixel
  const double ratio = 0.6, wgt = 0.7;
  auto eval = [&](const std::vector<double>& d, const std::vector<double>& a, const std::vector<double>& m,
                  const std::vector<double>& n, double* gd, double* ga, double* gm, double* gn) {
    return rendered_depth_normal_loss<double>(d.data(), a.data(), m.data(), n.data(), s.w, s.h, s.fx, s.fy, s.cx,
                                              s.cy, ratio, gd, ga, gm, gn, wgt);
  };
  std::vector<double> gd(hw, 0.0), ga(hw, 0.0), gm(hw, 0.0), gn(3 * hw, 0.0);
  eval(weighted, alpha, median, s.normal, gd.data(), ga.data(), gm.data(), gn.data());
  // A small step: at the clamped pixel the expected depth moves by h / 1e-4.
  expect_gradient([&](const std::vector<double>& d) { return wgt * eval(d, alpha, median, s.normal, 0, 0, 0, 0); },
                  weighted, gd, 1e-9, 1e-5);
  // The alpha also weights the pixels, as a constant: differentiate only through the division.
  std::vector<double> ga_fd(hw);
  for (size_t p = 0; p < hw; ++p) {
    auto f = [&](double da) {
      std::vector<double> a2 = alpha, d2 = weighted;
      const double base = std::max(alpha[p], 1e-4);
      // Same pixel weights, expected depth d / (alpha + da): move the depth instead.
      d2[p] = weighted[p] * base / std::max(alpha[p] + da, 1e-4);
      return wgt * eval(d2, a2, median, s.normal, 0, 0, 0, 0);
    };
    ga_fd[p] = (f(1e-7) - f(-1e-7)) / 2e-7;
    EXPECT_NEAR(ga[p], ga_fd[p], 1e-5 * (1 + std::abs(ga_fd[p]))) << p;
  }
  EXPECT_EQ(ga[3], 0.0) << "clamped pixel: no alpha gradient";
  expect_gradient([&](const std::vector<double>& m) { return wgt * eval(weighted, alpha, m, s.normal, 0, 0, 0, 0); },
                  median, gm, 1e-6, 1e-6);
  expect_gradient([&](const std::vector<double>& n) { return wgt * eval(weighted, alpha, median, n, 0, 0, 0, 0); },
                  s.normal, gn, 1e-6, 1e-6);
}
