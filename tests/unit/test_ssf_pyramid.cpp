// Screen-space glossy filter (render/ssf/glossy_filter.h): exactness at R_s = 0, constancy, blur growing with
// R_s, normal-aware weights, the weighted pyramid of coarse tracing (unit mass = unweighted, massless pixels
// ignored, sparse lattice ~ dense blur), finite-difference gradients in double (X and R_s, with and without
// masses), and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/util/error.h"
#include "render/ssf/glossy_filter.h"

namespace goris::ssf {
namespace {

template <class T>
std::vector<T> random_vec(std::size_t n, std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<T> v(n);
  for (T& x : v) x = T(u(rng));
  return v;
}

// Random normals, some zero (background) and some facing away, so every weight branch is exercised.
template <class T>
std::vector<T> random_normals(int h, int w, std::mt19937& rng) {
  std::vector<T> n = random_vec<T>(3 * std::size_t(h) * w, rng, -1.0, 1.0);
  const std::size_t plane = std::size_t(h) * w;
  for (std::size_t p = 0; p < plane; ++p) {
    n[2 * plane + p] = std::abs(n[2 * plane + p]) + T(0.6);  // mostly towards the camera: neighbours agree
    if (p % 11 == 3) n[p] = n[plane + p] = n[2 * plane + p] = T(0);
  }
  return n;
}

template <class T>
Buffer<T> buf(const std::vector<T>& v) {
  return Buffer<T>(v, Device::CPU);
}

TEST(SsfPyramid, ZeroRoughnessReturnsInputExactly) {
  std::mt19937 rng(1);
  const int C = 4, H = 37, W = 23;
  const std::vector<float> x = random_vec<float>(std::size_t(C) * H * W, rng, -3.0, 5.0);
  GlossyFilter<float> f;
  Buffer<float> out;
  f.forward(buf(x), C, H, W, buf(random_normals<float>(H, W, rng)), buf(std::vector<float>(std::size_t(H) * W, 0.0f)),
            out);
  const std::vector<float> o = out.to_host();
  for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(o[i], x[i]) << i;
}

TEST(SsfPyramid, ConstantImageStaysConstantAtEveryLevel) {
  std::mt19937 rng(2);
  const int C = 2, H = 29, W = 18;
  const std::size_t plane = std::size_t(H) * W;
  std::vector<double> x(C * plane);
  for (std::size_t p = 0; p < plane; ++p) {
    x[p] = 0.75;
    x[plane + p] = -2.5;
  }
  GlossyFilter<double> f;
  Buffer<double> out;
  f.forward(buf(x), C, H, W, buf(random_normals<double>(H, W, rng)), buf(random_vec<double>(plane, rng, 0.0, 1.0)),
            out);
  for (int k = 0; k < f.levels(); ++k) {
    const std::vector<double> l = f.level(k).to_host();
    const std::size_t m = std::size_t(f.dims(k).h) * f.dims(k).w;
    for (std::size_t p = 0; p < m; ++p) {
      ASSERT_NEAR(l[p], 0.75, 1e-12) << "level " << k;
      ASSERT_NEAR(l[m + p], -2.5, 1e-12) << "level " << k;
    }
  }
  const std::vector<double> o = out.to_host();
  for (std::size_t i = 0; i < o.size(); ++i) ASSERT_NEAR(o[i], x[i], 1e-12);
}

TEST(SsfPyramid, OddSizesHalveRoundingUp) {
  GlossyFilter<float> f;
  Buffer<float> out;
  f.forward(buf(std::vector<float>(13 * 1, 1.0f)), 1, 13, 1, buf(std::vector<float>(3 * 13, 0.0f)),
            buf(std::vector<float>(13, 1.0f)), out);
  const int expect_h[] = {13, 7, 4, 2, 1};
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(f.dims(k).h, expect_h[k]);
    EXPECT_EQ(f.dims(k).w, 1);
  }
  for (float v : out.to_host()) EXPECT_NEAR(v, 1.0f, 1e-6f);
}

// Largest step between horizontal neighbours of a vertical edge image: smaller = blurrier.
double max_step(const std::vector<double>& img, int H, int W) {
  double m = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x + 1 < W; ++x)
      m = std::max(m, std::abs(img[std::size_t(y) * W + x + 1] - img[std::size_t(y) * W + x]));
  return m;
}

TEST(SsfPyramid, SharpEdgeGetsBlurrierAsRoughnessGrows) {
  const int H = 32, W = 64;
  const std::size_t plane = std::size_t(H) * W;
  std::vector<double> x(plane), n(3 * plane, 0.0);
  for (int y = 0; y < H; ++y)
    for (int c = 0; c < W; ++c) x[std::size_t(y) * W + c] = c < W / 2 + 3 ? 0.0 : 1.0;
  for (std::size_t p = 0; p < plane; ++p) n[2 * plane + p] = 1.0;  // a flat surface facing the camera
  GlossyFilter<double> f;
  double prev = 2.0;
  for (double rs : {0.0, 0.2, 0.4, 0.6, 0.8, 1.0}) {
    Buffer<double> out;
    f.forward(buf(x), 1, H, W, buf(n), buf(std::vector<double>(plane, rs)), out);
    const double s = max_step(out.to_host(), H, W);
    EXPECT_LT(s, prev) << "R_s " << rs;
    prev = s;
  }
  EXPECT_LT(prev, 0.35);  // the coarsest level spreads the unit edge over several pixels
}

TEST(SsfPyramid, NormalWeightsKeepSurfacesApart) {
  // Left half faces the camera, right half is perpendicular to it: with the normal weights a coarse texel
  // next to the boundary averages only its own surface; with a plain Gaussian it mixes both.
  const int H = 16, W = 16;
  const std::size_t plane = std::size_t(H) * W;
  std::vector<double> x(plane), n(3 * plane, 0.0);
  for (int y = 0; y < H; ++y)
    for (int c = 0; c < W; ++c) {
      const std::size_t p = std::size_t(y) * W + c;
      const bool left = c < W / 2;
      x[p] = left ? 0.0 : 1.0;
      (left ? n[2 * plane + p] : n[p]) = 1.0;
    }
  const std::vector<double> rs(plane, 0.0);
  GlossyFilter<double> weighted(PyramidConfig{5, 8}), plain(PyramidConfig{5, 0});
  Buffer<double> out;
  weighted.forward(buf(x), 1, H, W, buf(n), buf(rs), out);
  plain.forward(buf(x), 1, H, W, buf(n), buf(rs), out);
  const int j = W / 4 - 1;  // level-1 column whose taps straddle the boundary at level 0
  const double a = weighted.level(1).to_host()[std::size_t(4) * (W / 2) + j];
  const double b = plain.level(1).to_host()[std::size_t(4) * (W / 2) + j];
  EXPECT_LT(a, 1e-3);
  EXPECT_GT(b, 0.05);
}

struct Problem {
  int C = 2, H = 13, W = 11;
  std::vector<double> x, n, rs, g_out;
};

Problem make_problem(unsigned seed) {
  Problem p;
  std::mt19937 rng(seed);
  const std::size_t plane = std::size_t(p.H) * p.W;
  p.x = random_vec<double>(p.C * plane, rng, -1.0, 1.0);
  p.n = random_normals<double>(p.H, p.W, rng);
  p.g_out = random_vec<double>(p.C * plane, rng, -1.0, 1.0);
  // Continuous levels away from the integers, where the level blend has a kink.
  std::uniform_int_distribution<int> level(0, 3);
  std::uniform_real_distribution<double> frac(0.1, 0.9);
  p.rs.resize(plane);
  for (double& r : p.rs) r = (level(rng) + frac(rng)) / 4.0;
  return p;
}

double loss(const Problem& p) {
  GlossyFilter<double> f;
  Buffer<double> out;
  f.forward(buf(p.x), p.C, p.H, p.W, buf(p.n), buf(p.rs), out);
  const std::vector<double> o = out.to_host();
  double l = 0;
  for (std::size_t i = 0; i < o.size(); ++i) l += o[i] * p.g_out[i];
  return l;
}

TEST(SsfPyramid, GradientsMatchFiniteDifferences) {
  for (unsigned seed : {3u, 4u}) {
    Problem p = make_problem(seed);
    GlossyFilter<double> f;
    Buffer<double> out;
    f.forward(buf(p.x), p.C, p.H, p.W, buf(p.n), buf(p.rs), out);
    Buffer<double> gx = buf(std::vector<double>(p.x.size(), 0.5)), grs = buf(std::vector<double>(p.rs.size(), -0.25));
    f.backward(buf(p.g_out), &gx, &grs);  // adds onto the 0.5 / -0.25 already there
    const std::vector<double> ax = gx.to_host(), ars = grs.to_host();
    const double h = 1e-6;
    for (std::size_t i = 0; i < p.x.size(); ++i) {
      Problem q = p;
      q.x[i] += h;
      const double lp = loss(q);
      q.x[i] -= 2 * h;
      const double fd = (lp - loss(q)) / (2 * h);
      ASSERT_NEAR(ax[i] - 0.5, fd, 1e-8) << "dX " << i << " seed " << seed;
    }
    for (std::size_t i = 0; i < p.rs.size(); ++i) {
      Problem q = p;
      q.rs[i] += h;
      const double lp = loss(q);
      q.rs[i] -= 2 * h;
      const double fd = (lp - loss(q)) / (2 * h);
      ASSERT_NEAR(ars[i] + 0.25, fd, 1e-7 * (1 + std::abs(fd))) << "dR_s " << i << " seed " << seed;
    }
  }
}

// Weighted pyramid (coarse tracing's mass image): masses on a 2x2 lattice, 0 elsewhere, plus some
// fractional and zero masses so that every branch of the normalisation is exercised.
template <class T>
std::vector<T> lattice_mass(int h, int w, std::mt19937& rng, bool fractional) {
  std::vector<T> m(std::size_t(h) * w, T(0));
  std::uniform_real_distribution<double> u(0.2, 1.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * w + x;
      if (y % 2 == 0 && x % 2 == 0) m[p] = T(1);
      if (fractional && (p % 7 == 2)) m[p] = T(u(rng));
    }
  return m;
}

TEST(SsfPyramid, UnitMassGivesTheUnweightedPyramid) {
  std::mt19937 rng(11);
  const int C = 3, H = 21, W = 17;
  const std::size_t plane = std::size_t(H) * W;
  const std::vector<double> x = random_vec<double>(C * plane, rng, -1.0, 2.0), n = random_normals<double>(H, W, rng),
                            rs = random_vec<double>(plane, rng, 0.0, 1.0);
  GlossyFilter<double> plain, weighted;
  Buffer<double> a, b;
  const Buffer<double> ones = buf(std::vector<double>(plane, 1.0));
  plain.forward(buf(x), C, H, W, buf(n), buf(rs), a);
  weighted.forward(buf(x), C, H, W, buf(n), buf(rs), b, &ones);
  ASSERT_TRUE(weighted.weighted());
  ASSERT_FALSE(plain.weighted());
  EXPECT_THROW(plain.mass(0), Error);
  const std::vector<double> ha = a.to_host(), hb = b.to_host();
  for (std::size_t i = 0; i < ha.size(); ++i) ASSERT_NEAR(ha[i], hb[i], 1e-12) << i;
  for (int k = 1; k < weighted.levels(); ++k)
    for (double m : weighted.mass(k).to_host()) ASSERT_NEAR(m, 1.0, 1e-12) << "level " << k;
}

TEST(SsfPyramid, PixelsWithoutMassNeverEnterTheOutput) {
  std::mt19937 rng(12);
  const int C = 2, H = 26, W = 19;
  const std::size_t plane = std::size_t(H) * W;
  const std::vector<double> mass = lattice_mass<double>(H, W, rng, true), n = random_normals<double>(H, W, rng),
                            rs = random_vec<double>(plane, rng, 0.0, 1.0);
  std::vector<double> x = random_vec<double>(C * plane, rng, -1.0, 1.0);
  const Buffer<double> m = buf(mass);
  GlossyFilter<double> f;
  Buffer<double> out1, out2;
  f.forward(buf(x), C, H, W, buf(n), buf(rs), out1, &m);
  for (std::size_t p = 0; p < plane; ++p)
    if (mass[p] == 0.0)
      for (int c = 0; c < C; ++c) x[c * plane + p] = 1e3 * (c + 1);  // garbage where nothing was traced
  f.forward(buf(x), C, H, W, buf(n), buf(rs), out2, &m);
  EXPECT_EQ(out1.to_host(), out2.to_host());
  // A constant image stays constant wherever a texel has mass; massless texels are 0.
  std::vector<double> c(plane, 0.625);
  f.forward(buf(c), 1, H, W, buf(n), buf(rs), out1, &m);
  for (int k = 1; k < f.levels(); ++k) {
    const std::vector<double> l = f.level(k).to_host(), lm = f.mass(k).to_host();
    for (std::size_t p = 0; p < l.size(); ++p) {
      ASSERT_GE(lm[p], 0.0);
      ASSERT_LE(lm[p], 1.0 + 1e-12);
      ASSERT_NEAR(l[p], lm[p] > 0 ? 0.625 : 0.0, 1e-12) << "level " << k;
    }
  }
  const std::vector<double> o = out1.to_host();
  for (std::size_t p = 0; p < plane; ++p) {
    const bool reads_level0 = rs[p] * (f.levels() - 1) < 1.0;
    if (!reads_level0 || mass[p] > 0) {
      ASSERT_NEAR(o[p], 0.625, 1e-12) << p;
    }
  }
}

TEST(SsfPyramid, SparseLatticeEstimatesTheDenseBlur) {
  // A smooth image traced on a 2x2 lattice: at blur levels >= 1 the weighted pyramid stays close to the
  // fully traced one, while feeding the untraced pixels in as zeros would darken it by about 3/4.
  const int H = 48, W = 64;
  const std::size_t plane = std::size_t(H) * W;
  std::vector<double> x(plane), n(3 * plane, 0.0), mass(plane, 0.0), zeroed(plane, 0.0);
  for (int y = 0; y < H; ++y)
    for (int c = 0; c < W; ++c) {
      const std::size_t p = std::size_t(y) * W + c;
      x[p] = 0.5 + 0.4 * std::sin(c * 0.2) * std::cos(y * 0.15);
      n[2 * plane + p] = 1.0;
      if (y % 2 == 0 && c % 2 == 0) mass[p] = 1.0, zeroed[p] = x[p];
    }
  const std::vector<double> rs(plane, 0.4);  // level 1.6: reads levels 1 and 2 only
  GlossyFilter<double> f;
  Buffer<double> dense, sparse, naive;
  const Buffer<double> m = buf(mass);
  f.forward(buf(x), 1, H, W, buf(n), buf(rs), dense);
  f.forward(buf(zeroed), 1, H, W, buf(n), buf(rs), sparse, &m);
  f.forward(buf(zeroed), 1, H, W, buf(n), buf(rs), naive);
  const std::vector<double> d = dense.to_host(), s = sparse.to_host(), z = naive.to_host();
  double err = 0, err_naive = 0;
  for (std::size_t p = 0; p < plane; ++p) {
    err = std::max(err, std::abs(s[p] - d[p]));
    err_naive = std::max(err_naive, std::abs(z[p] - d[p]));
  }
  EXPECT_LT(err, 0.03);
  EXPECT_GT(err_naive, 0.2);
}

TEST(SsfPyramid, WeightedGradientsMatchFiniteDifferences) {
  for (unsigned seed : {13u, 14u}) {
    Problem p = make_problem(seed);
    std::mt19937 rng(seed + 100);
    const Buffer<double> m = buf(lattice_mass<double>(p.H, p.W, rng, true));
    auto weighted_loss = [&](const Problem& q) {
      GlossyFilter<double> f;
      Buffer<double> out;
      f.forward(buf(q.x), q.C, q.H, q.W, buf(q.n), buf(q.rs), out, &m);
      const std::vector<double> o = out.to_host();
      double l = 0;
      for (std::size_t i = 0; i < o.size(); ++i) l += o[i] * q.g_out[i];
      return l;
    };
    GlossyFilter<double> f;
    Buffer<double> out;
    f.forward(buf(p.x), p.C, p.H, p.W, buf(p.n), buf(p.rs), out, &m);
    Buffer<double> gx = buf(std::vector<double>(p.x.size(), 0.0)), grs = buf(std::vector<double>(p.rs.size(), 0.0));
    f.backward(buf(p.g_out), &gx, &grs);
    const std::vector<double> ax = gx.to_host(), ars = grs.to_host(), mh = m.to_host();
    const double h = 1e-6;
    std::size_t massless_zero = 0;
    for (std::size_t i = 0; i < p.x.size(); ++i) {
      Problem q = p;
      q.x[i] += h;
      const double lp = weighted_loss(q);
      q.x[i] -= 2 * h;
      const double fd = (lp - weighted_loss(q)) / (2 * h);
      ASSERT_NEAR(ax[i], fd, 1e-8) << "dX " << i << " seed " << seed;
      if (mh[i % mh.size()] == 0.0) massless_zero += ax[i] == 0.0;
    }
    EXPECT_GT(massless_zero, p.x.size() / 4);  // untraced pixels get exactly no gradient
    for (std::size_t i = 0; i < p.rs.size(); ++i) {
      Problem q = p;
      q.rs[i] += h;
      const double lp = weighted_loss(q);
      q.rs[i] -= 2 * h;
      const double fd = (lp - weighted_loss(q)) / (2 * h);
      ASSERT_NEAR(ars[i], fd, 1e-7 * (1 + std::abs(fd))) << "dR_s " << i << " seed " << seed;
    }
  }
}

TEST(SsfPyramid, BadInputThrows) {
  const int C = 2, H = 5, W = 4;
  const std::size_t plane = std::size_t(H) * W;
  std::vector<float> x(C * plane, 0.5f), n(3 * plane, 0.0f), rs(plane, 0.3f);
  GlossyFilter<float> f;
  Buffer<float> out;
  EXPECT_THROW(f.backward(buf(x), nullptr, nullptr), Error);  // before forward
  EXPECT_THROW(f.forward(buf(std::vector<float>(C * plane - 1)), C, H, W, buf(n), buf(rs), out), Error);
  EXPECT_THROW(f.forward(buf(x), C, H, W, buf(std::vector<float>(plane)), buf(rs), out), Error);
  EXPECT_THROW(f.forward(buf(x), C, H, W, buf(n), buf(std::vector<float>(plane + 1)), out), Error);
  EXPECT_THROW(f.forward(buf(x), 0, H, W, buf(n), buf(rs), out), Error);
  std::vector<float> bad = x;
  bad[7] = std::numeric_limits<float>::quiet_NaN();
  try {
    f.forward(buf(bad), C, H, W, buf(n), buf(rs), out);
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("glossy filter: input image has a NaN"), std::string::npos) << e.what();
  }
  bad = rs;
  bad[0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(f.forward(buf(x), C, H, W, buf(n), buf(bad), out), Error);
  f.forward(buf(x), C, H, W, buf(n), buf(rs), out);
  Buffer<float> g_small(plane);
  EXPECT_THROW(f.backward(buf(x), &g_small, nullptr), Error);
  const Buffer<float> short_mass = buf(std::vector<float>(plane - 1, 1.0f));
  EXPECT_THROW(f.forward(buf(x), C, H, W, buf(n), buf(rs), out, &short_mass), Error);
  std::vector<float> mass(plane, 1.0f);
  mass[3] = -0.5f;
  const Buffer<float> negative = buf(mass);
  EXPECT_THROW(f.forward(buf(x), C, H, W, buf(n), buf(rs), out, &negative), Error);
  mass[3] = std::numeric_limits<float>::quiet_NaN();
  const Buffer<float> nan_mass = buf(mass);
  EXPECT_THROW(f.forward(buf(x), C, H, W, buf(n), buf(rs), out, &nan_mass), Error);
  EXPECT_THROW(GlossyFilter<float>(PyramidConfig{1, 8}), Error);
  EXPECT_THROW(GlossyFilter<float>(PyramidConfig{kMaxLevels + 1, 8}), Error);
}

}  // namespace
}  // namespace goris::ssf
