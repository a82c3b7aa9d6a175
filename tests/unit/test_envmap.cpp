// The environment cube map: face mapping, the prefilter and its adjoint, lookups and their gradients (to
// texels, direction, roughness) by finite differences in double precision, the EnvironmentMap class wiring
// (float against the double reference) and its input checks; the distance-aware lookup (env_proxy_math.h).
#include <cmath>
#include <random>
#include <vector>

#include "core/util/error.h"
#include "render/envmap/cube_map_ops.h"
#include "render/envmap/environment_map.h"
#include "render/envmap/env_proxy_math.h"
#include "tests/support/test_support.h"

using namespace goris;
using namespace goris::envmap;

namespace {

constexpr int kR = 8, kL = 4;  // 8x8 faces down to 1x1

std::vector<double> random_values(std::size_t n, std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (auto& x : v) x = u(rng);
  return v;
}

// Random directions away from face edges (|s|, |t| < 0.9 |major|) so a small step never changes the face.
std::vector<double> random_dirs(std::size_t n, std::mt19937& rng) {
  std::normal_distribution<double> g;
  std::vector<double> d;
  while (d.size() < 3 * n) {
    const Vec3<double> v(g(rng), g(rng), g(rng));
    const CubeCoord<double> c = cube_coord(v);
    if (std::abs(c.sc) > 0.9 * c.ma || std::abs(c.tc) > 0.9 * c.ma) continue;
    d.insert(d.end(), {v.x, v.y, v.z});
  }
  return d;
}

// Full chain from level-0 values (a copy of level 0 followed by the prefiltered levels).
std::vector<double> chain_from_level0(const std::vector<double>& level0, int R, int L) {
  std::vector<double> chain(chain_size(R, L)), scratch(std::size_t(6) * R * (R / 2) * 3 + 1);
  std::copy(level0.begin(), level0.end(), chain.begin());
  ops::prefilter(Device::CPU, chain.data(), scratch.data(), R, L);
  return chain;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

TEST(EnvMap, FaceMappingFollowsTheCubeMapConvention) {
  const double s = 0.3;
  struct Case {
    Vec3<double> d;
    int face;
    double u, v;
  } cases[] = {{{1, 0, 0}, 0, 0.5, 0.5}, {{-1, 0, 0}, 1, 0.5, 0.5}, {{0, 1, 0}, 2, 0.5, 0.5},
               {{0, -1, 0}, 3, 0.5, 0.5}, {{0, 0, 1}, 4, 0.5, 0.5}, {{0, 0, -1}, 5, 0.5, 0.5},
               {{1, 0, -s}, 0, 0.5 + s / 2, 0.5}, {{0, 0, 1}, 4, 0.5, 0.5}, {{s, -s, 1}, 4, 0.5 + s / 2, 0.5 + s / 2}};
  for (const Case& c : cases) {
    const CubeCoord<double> cc = cube_coord(c.d * 2.5);  // any length
    EXPECT_EQ(cc.face, c.face);
    EXPECT_NEAR(cc.u, c.u, 1e-12);
    EXPECT_NEAR(cc.v, c.v, 1e-12);
  }
}

TEST(EnvMap, RoughnessMapsToLevelsMonotonically) {
  double dl = 0, prev = -1;
  for (double r = 0; r <= 1.0001; r += 0.05) {
    const double l = roughness_to_level(r, 256, 9, &dl);
    EXPECT_GE(l, prev);
    EXPECT_GE(l, 0);
    EXPECT_LE(l, 8);
    prev = l;
  }
  EXPECT_EQ(roughness_to_level(0.0, 256, 9, &dl), 0);
  EXPECT_EQ(roughness_to_level(1.0, 256, 9, &dl), 8);  // a full chain: the 1x1 level at r = 1
  EXPECT_EQ(roughness_to_level(1.0, 256, 5, &dl), 4);  // a short chain clamps
}

TEST(EnvMap, PrefilterKeepsConstantsAndAverages) {
  std::vector<double> level0(std::size_t(6) * kR * kR * 3, 0.7);
  const auto chain = chain_from_level0(level0, kR, kL);
  for (double v : chain) EXPECT_NEAR(v, 0.7, 1e-12);
  // Each face's 1x1 level is the face's mean (the clamped binomial kernel sums to one per output).
  std::mt19937 rng(3);
  level0 = random_values(level0.size(), rng, 0, 1);
  const auto c2 = chain_from_level0(level0, kR, kL);
  const long long top = level_offset(kR, kL - 1);
  for (int f = 0; f < 6; ++f) {
    double mean = 0;
    for (int i = 0; i < kR * kR; ++i) mean += level0[(std::size_t(f) * kR * kR + i) * 3];
    mean /= kR * kR;
    // Not exactly the mean (edge taps are clamped, so edge texels weigh more) but close to it.
    EXPECT_NEAR(c2[top + f * 3], mean, 0.1);
  }
}

TEST(EnvMap, PrefilterAdjointMatchesForward) {
  std::mt19937 rng(7);
  for (int R : {2, 8, 16}) {
    int L = 1;
    while ((R >> (L - 1)) > 1) ++L;
    const std::size_t n0 = std::size_t(6) * R * R * 3;
    const auto x = random_values(n0, rng, -1, 1);
    auto y = random_values(chain_size(R, L), rng, -1, 1);
    const auto Ax = chain_from_level0(x, R, L);
    std::vector<double> scratch(std::size_t(6) * R * (R / 2) * 3 + 1);
    const double lhs = dot(Ax, y);
    ops::prefilter_adjoint(Device::CPU, y.data(), scratch.data(), R, L);
    const double rhs = dot(x, std::vector<double>(y.begin(), y.begin() + n0));
    EXPECT_NEAR(lhs, rhs, 1e-10 * (1 + std::abs(lhs))) << "R = " << R;
  }
}

TEST(EnvMap, LookupGradientsMatchFiniteDifferences) {
  std::mt19937 rng(11);
  const std::size_t n = 40;
  auto chain = random_values(chain_size(kR, kL), rng, 0.1, 2.0);
  const auto dirs0 = random_dirs(n, rng);
  const auto rough0 = random_values(n, rng, 0.36, 0.95);  // level in (0, 3): no clamp
  const auto w = random_values(3 * n, rng, -1, 1);
  auto loss = [&](const std::vector<double>& ch, const std::vector<double>& dirs, const std::vector<double>& r) {
    std::vector<double> out(3 * n);
    ops::lookup(Device::CPU, CubeMipsT<double>{ch.data(), kR, kL}, dirs.data(), r.data(), n, out.data());
    return dot(out, w);
  };
  std::vector<double> gchain(chain.size(), 0.0), gdirs(3 * n), grough(n);
  ops::lookup_backward(Device::CPU, CubeMipsT<double>{chain.data(), kR, kL}, dirs0.data(), rough0.data(), w.data(), n,
                       gchain.data(), gdirs.data(), grough.data());
  const double h = 1e-6;
  // Texels: the lookup is linear in them, so central differences are exact up to rounding.
  for (std::size_t i = 0; i < chain.size(); ++i) {
    auto cp = chain, cm = chain;
    cp[i] += h, cm[i] -= h;
    EXPECT_NEAR((loss(cp, dirs0, rough0) - loss(cm, dirs0, rough0)) / (2 * h), gchain[i], 1e-7) << "texel " << i;
  }
  for (std::size_t i = 0; i < 3 * n; ++i) {
    auto dp = dirs0, dm = dirs0;
    dp[i] += h, dm[i] -= h;
    const double fd = (loss(chain, dp, rough0) - loss(chain, dm, rough0)) / (2 * h);
    EXPECT_NEAR(fd, gdirs[i], 1e-5 * (1 + std::abs(fd))) << "direction component " << i;
  }
  for (std::size_t i = 0; i < n; ++i) {
    auto rp = rough0, rm = rough0;
    rp[i] += h, rm[i] -= h;
    const double fd = (loss(chain, dirs0, rp) - loss(chain, dirs0, rm)) / (2 * h);
    EXPECT_NEAR(fd, grough[i], 1e-5 * (1 + std::abs(fd))) << "roughness " << i;
  }
}

// Parameters -> exp -> prefilter -> lookups, and back through lookup_backward, the adjoint and exp'.
TEST(EnvMap, ParameterGradientsThroughTheWholeChain) {
  std::mt19937 rng(5);
  const std::size_t n = 30, n0 = std::size_t(6) * kR * kR * 3;
  const auto params = random_values(n0, rng, -1, 1);
  const auto dirs = random_dirs(n, rng);
  const auto rough = random_values(n, rng, 0.0, 1.0);
  const auto w = random_values(3 * n, rng, -1, 1);
  auto loss = [&](const std::vector<double>& p) {
    std::vector<double> level0(n0);
    ops::activate(Device::CPU, p.data(), level0.data(), n0);
    const auto chain = chain_from_level0(level0, kR, kL);
    std::vector<double> out(3 * n);
    ops::lookup(Device::CPU, CubeMipsT<double>{chain.data(), kR, kL}, dirs.data(), rough.data(), n, out.data());
    return dot(out, w);
  };
  std::vector<double> level0(n0);
  ops::activate(Device::CPU, params.data(), level0.data(), n0);
  const auto chain = chain_from_level0(level0, kR, kL);
  std::vector<double> gchain(chain.size(), 0.0), scratch(std::size_t(6) * kR * (kR / 2) * 3), gparams(n0, 0.0);
  ops::lookup_backward(Device::CPU, CubeMipsT<double>{chain.data(), kR, kL}, dirs.data(), rough.data(), w.data(), n,
                       gchain.data(), nullptr, nullptr);
  ops::prefilter_adjoint(Device::CPU, gchain.data(), scratch.data(), kR, kL);
  ops::activate_backward(Device::CPU, level0.data(), gchain.data(), gparams.data(), n0);
  double norm = 0;
  for (std::size_t i = 0; i < n0; ++i) {
    auto pp = params, pm = params;
    pp[i] += 1e-6, pm[i] -= 1e-6;
    const double fd = (loss(pp) - loss(pm)) / 2e-6;
    EXPECT_NEAR(fd, gparams[i], 1e-6 * (1 + std::abs(fd))) << "parameter " << i;
    norm += std::abs(gparams[i]);
  }
  EXPECT_GT(norm, 0.1);  // the lookups do reach the parameters
}

TEST(EnvMap, ConstantMapReturnsItsValueForAnyDirectionAndRoughness) {
  EnvironmentMap env(16, Device::CPU, 0.7f);
  EXPECT_EQ(env.levels(), 5);
  std::mt19937 rng(1);
  const std::size_t n = 50;
  const auto d64 = random_dirs(n, rng);
  const auto r64 = random_values(n, rng, 0, 1);
  std::vector<float> dirs(d64.begin(), d64.end()), rough(r64.begin(), r64.end()), out(3 * n);
  env.lookup(dirs.data(), rough.data(), n, out.data());
  for (float v : out) EXPECT_NEAR(v, 0.7f, 1e-6f);
}

// The float class must agree with the double reference composed from the ops.
TEST(EnvMap, ClassBackwardAgreesWithReference) {
  EnvironmentMap env(kR, Device::CPU, 0.5f, kL);
  std::mt19937 rng(9);
  const std::size_t n = 25, n0 = env.param_count();
  const auto p64 = random_values(n0, rng, -1, 1);
  for (std::size_t i = 0; i < n0; ++i) env.params()[i] = float(p64[i]);
  env.update();
  const auto d64 = random_dirs(n, rng);
  const auto r64 = random_values(n, rng, 0, 1);
  const auto w64 = random_values(3 * n, rng, -1, 1);
  std::vector<float> dirs(d64.begin(), d64.end()), rough(r64.begin(), r64.end()), w(w64.begin(), w64.end());
  env.lookup_backward(dirs.data(), rough.data(), w.data(), n, nullptr, nullptr);
  env.backward();

  std::vector<double> pd(n0), level0(n0), gparams(n0, 0.0), scratch(std::size_t(6) * kR * (kR / 2) * 3);
  for (std::size_t i = 0; i < n0; ++i) pd[i] = double(env.params()[i]);
  std::vector<double> dd(dirs.begin(), dirs.end()), rd(rough.begin(), rough.end()), wd(w.begin(), w.end());
  ops::activate(Device::CPU, pd.data(), level0.data(), n0);
  const auto chain = chain_from_level0(level0, kR, kL);
  std::vector<double> gchain(chain.size(), 0.0);
  ops::lookup_backward(Device::CPU, CubeMipsT<double>{chain.data(), kR, kL}, dd.data(), rd.data(), wd.data(), n,
                       gchain.data(), nullptr, nullptr);
  ops::prefilter_adjoint(Device::CPU, gchain.data(), scratch.data(), kR, kL);
  ops::activate_backward(Device::CPU, level0.data(), gchain.data(), gparams.data(), n0);
  for (std::size_t i = 0; i < n0; ++i) EXPECT_NEAR(env.grads()[i], gparams[i], 1e-5 * (1 + std::abs(gparams[i])));
  // backward() consumed the mip gradients: a second call adds nothing.
  const std::vector<float> before = env.grads().to_host();
  env.backward();
  EXPECT_EQ(env.grads().to_host(), before);
  env.zero_grad();
  for (std::size_t i = 0; i < n0; ++i) ASSERT_EQ(env.grads()[i], 0.0f);
}

TEST(EnvMap, EquirectPreviewOfAConstantMap) {
  EnvironmentMap env(8, Device::CPU, 0.25f);
  const auto img = env.equirect_image(32);
  ASSERT_EQ(img.size(), std::size_t(32 * 16 * 3));
  for (float v : img) EXPECT_NEAR(v, 0.25f, 1e-6f);
}

TEST(EnvMap, BadInputIsRejected) {
  EXPECT_THROW(EnvironmentMap(100, Device::CPU), Error);    // not a power of two
  EXPECT_THROW(EnvironmentMap(0, Device::CPU), Error);
  EXPECT_THROW(EnvironmentMap(16, Device::CPU, 0.5f, 6), Error);  // 16 allows 5 levels
  EXPECT_THROW(EnvironmentMap(16, Device::CPU, -1.0f), Error);
  EnvironmentMap env(4, Device::CPU);
  env.params()[5] = std::nanf("");
  try {
    env.update();
    FAIL() << "a NaN parameter was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("environment map"), std::string::npos);
  }
  EXPECT_THROW(env.lookup(nullptr, nullptr, 3, nullptr), Error);
  EXPECT_THROW(env.equirect_image(1), Error);
  if (!cuda_compiled()) EXPECT_THROW(EnvironmentMap(4, Device::CUDA), Error);
}

// The environment on a sphere: a point on it is read in one direction from every surface point inside
// (what lets one map hold a near light), a huge sphere reads omega_r, points outside read omega_r.
TEST(EnvProxy, APointOnTheSphereIsSeenInOneDirectionFromEverywhere) {
  const Vec3<double> c(0.3, -0.2, 0.5), light(1.0, 2.0, 3.5);
  const double R = glm::length(light - c);
  const Vec3<double> expected = (light - c) / R;
  for (const Vec3<double> x : {Vec3<double>(0, 0, 0), Vec3<double>(1, -1, 0.2), Vec3<double>(-1.5, 0.5, 0)}) {
    const Vec3<double> w = glm::normalize(light - x);
    const ProxyHit<double> h = proxy_hit(x, w, c, R);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(glm::length(h.dir - expected), 0.0, 1e-12);
    EXPECT_NEAR(h.t, glm::length(light - x), 1e-12);
  }
  const Vec3<double> x(0.4, 0.1, -0.3), w = glm::normalize(Vec3<double>(0.2, -0.7, 0.4));
  EXPECT_NEAR(glm::length(proxy_hit(x, w, c, 1e7).dir - w), 0.0, 1e-6);
  const ProxyHit<double> outside = proxy_hit(Vec3<double>(10, 0, 0), w, c, R);
  EXPECT_FALSE(outside.hit);
  EXPECT_EQ(outside.dir, w);
  EXPECT_FALSE(proxy_hit(x, w, c, 0.0).hit);  // radius 0: at infinity
}

TEST(EnvProxy, DirectionGradientsMatchFiniteDifferences) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  const Vec3<double> c(0.2, 0.1, -0.3);
  const double R = 3.0, h = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3<double> x = c + 0.8 * R * glm::normalize(Vec3<double>(g(rng), g(rng), g(rng))) * std::abs(g(rng)) / 3.0;
    const Vec3<double> w = glm::normalize(Vec3<double>(g(rng), g(rng), g(rng)));
    const Vec3<double> gout(g(rng), g(rng), g(rng));
    if (!(glm::length(x - c) < R)) continue;
    const ProxyHit<double> hit = proxy_hit(x, w, c, R);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(glm::length(hit.dir), 1.0, 1e-12);
    Vec3<double> dw(0.0), dx(0.0);
    proxy_hit_vjp(hit, w, R, gout, &dw, &dx);
    for (int k = 0; k < 3; ++k) {
      Vec3<double> wp = w, wm = w, xp = x, xm = x;
      wp[k] += h, wm[k] -= h, xp[k] += h, xm[k] -= h;
      const double fdw = glm::dot(gout, proxy_hit(x, wp, c, R).dir - proxy_hit(x, wm, c, R).dir) / (2 * h);
      const double fdx = glm::dot(gout, proxy_hit(xp, w, c, R).dir - proxy_hit(xm, w, c, R).dir) / (2 * h);
      EXPECT_NEAR(dw[k], fdw, 1e-6 * (1 + std::abs(fdw))) << "trial " << trial << " w[" << k << "]";
      EXPECT_NEAR(dx[k], fdx, 1e-6 * (1 + std::abs(fdx))) << "trial " << trial << " x[" << k << "]";
    }
  }
}
