// The glossy filter (plain and weighted) and the roughness net on CUDA against the CPU reference on the same
// inputs (forward, backward, one Adam step). Skipped (with a message) where no CUDA device is present.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "render/ssf/glossy_filter.h"
#include "train/optimizer/flat_adam.h"
#include "render/ssf/roughness_net.h"
#include "tests/support/test_support.h"

using namespace goris;
using namespace goris::ssf;

namespace {

std::vector<float> random_vec(std::size_t n, std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

void expect_close(const Buffer<float>& cpu, const Buffer<float>& gpu, const char* what) {
  const std::vector<float> a = cpu.to_host(), b = gpu.to_host();
  ASSERT_EQ(a.size(), b.size()) << what;
  float scale = 0;
  for (float v : a) scale = std::max(scale, std::abs(v));
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_NEAR(a[i], b[i], 1e-4f * std::max(1.0f, std::max(std::abs(a[i]), 1e-2f * scale))) << what << " " << i;
}

TEST(SsfCuda, GlossyFilterMatchesCpu) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(5);
  const int C = 4, H = 67, W = 45;
  const std::size_t plane = std::size_t(H) * W;
  const std::vector<float> x = random_vec(C * plane, rng, 0, 2), n = random_vec(3 * plane, rng, -1, 1),
                           rs = random_vec(plane, rng, 0, 1), g = random_vec(C * plane, rng, -1, 1);
  Buffer<float> out[2], gx[2], grs[2];
  int i = 0;
  for (Device d : {Device::CPU, Device::CUDA}) {
    GlossyFilter<float> f;
    f.forward(Buffer<float>(x, d), C, H, W, Buffer<float>(n, d), Buffer<float>(rs, d), out[i]);
    gx[i] = Buffer<float>(C * plane, d);
    grs[i] = Buffer<float>(plane, d);
    gx[i].fill_zero();
    grs[i].fill_zero();
    f.backward(Buffer<float>(g, d), &gx[i], &grs[i]);
    ++i;
  }
  expect_close(out[0], out[1], "output");
  expect_close(gx[0], gx[1], "dL/dX");
  expect_close(grs[0], grs[1], "dL/dR_s");
}

TEST(SsfCuda, WeightedGlossyFilterMatchesCpu) {
  // Coarse tracing's weighted pyramid: masses on a 2x2 lattice (0 elsewhere) and some fractional ones.
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(7);
  const int C = 4, H = 61, W = 50;
  const std::size_t plane = std::size_t(H) * W;
  const std::vector<float> x = random_vec(C * plane, rng, 0, 2), n = random_vec(3 * plane, rng, -1, 1),
                           rs = random_vec(plane, rng, 0, 1), g = random_vec(C * plane, rng, -1, 1);
  std::vector<float> mass(plane, 0.0f);
  for (int y = 0; y < H; y += 2)
    for (int c = 0; c < W; c += 2) mass[std::size_t(y) * W + c] = 1.0f;
  for (std::size_t p = 5; p < plane; p += 13) mass[p] = 0.5f;
  Buffer<float> out[2], gx[2], grs[2];
  int i = 0;
  for (Device d : {Device::CPU, Device::CUDA}) {
    GlossyFilter<float> f;
    const Buffer<float> m(mass, d);
    f.forward(Buffer<float>(x, d), C, H, W, Buffer<float>(n, d), Buffer<float>(rs, d), out[i], &m);
    gx[i] = Buffer<float>(C * plane, d);
    grs[i] = Buffer<float>(plane, d);
    gx[i].fill_zero();
    grs[i].fill_zero();
    f.backward(Buffer<float>(g, d), &gx[i], &grs[i]);
    ++i;
  }
  expect_close(out[0], out[1], "weighted output");
  expect_close(gx[0], gx[1], "weighted dL/dX");
  expect_close(grs[0], grs[1], "weighted dL/dR_s");
}

// The net on both devices, on the whole image or a window (pixel_window.h).
void expect_net_matches_cpu(const PixelWindow* window) {
  std::mt19937 rng(6);
  const int H = 70, W = 53;
  const std::size_t plane = std::size_t(H) * W;
  const std::vector<float> in = random_vec(3 * plane, rng, 0, 2), g = random_vec(plane, rng, -1, 1);
  Buffer<float> rs[2], gin[2], grads[2], params[2];
  int i = 0;
  for (Device d : {Device::CPU, Device::CUDA}) {
    RoughnessNet<float> net(NetConfig{}, d, 9);
    FlatAdam adam(net.param_count(), net.device());
    net.forward(Buffer<float>(in, d), H, W, rs[i], window);
    gin[i] = Buffer<float>(3 * plane, d);
    gin[i].fill_zero();
    net.backward(Buffer<float>(g, d), &gin[i]);
    grads[i] = net.grads().copy_to(d);
    adam.step(net.params(), net.grads(), 1e-3f, "roughness net");
    params[i] = net.params().copy_to(d);
    ++i;
  }
  expect_close(rs[0], rs[1], "R_s");
  expect_close(gin[0], gin[1], "dL/dinput");
  expect_close(grads[0], grads[1], "dL/dparams");
  // Adam's first step is lr * sign(g): compare where the gradient is clearly non-zero (its sign is then the
  // same on both devices).
  const std::vector<float> p0 = params[0].to_host(), p1 = params[1].to_host(), g0 = grads[0].to_host();
  float gmax = 0;
  for (float v : g0) gmax = std::max(gmax, std::abs(v));
  for (std::size_t k = 0; k < p0.size(); ++k)
    if (std::abs(g0[k]) > 1e-3f * gmax) ASSERT_NEAR(p0[k], p1[k], 1e-5f) << "parameter " << k << " after Adam";
}

TEST(SsfCuda, RoughnessNetMatchesCpu) {
  GORIS_REQUIRE_GPU();
  expect_net_matches_cpu(nullptr);
}

TEST(SsfCuda, RoughnessNetOnAWindowMatchesCpu) {
  GORIS_REQUIRE_GPU();
  const PixelWindow window{8, 11, 41, 57};
  expect_net_matches_cpu(&window);
}

}  // namespace
