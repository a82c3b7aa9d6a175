// The roughness net run on a window (render/ssf/pixel_window.h): the window's bounds, and the net's output
// and gradients on the window equal to the whole image's, bit for bit, wherever the shading reads them - for
// float (what training runs) and double; a window one pixel too small differs, so the comparison can fail.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/util/error.h"
#include "render/ssf/pixel_window.h"
#include "render/ssf/roughness_net.h"

namespace goris::ssf {
namespace {

// An alpha image with an irregular blob of surface pixels (alpha 0.9) inside [bx0, bx1] x [by0, by1] and a
// faint haze (alpha 0.3, below the threshold) elsewhere.
std::vector<float> blob_alpha(int w, int h, int bx0, int by0, int bx1, int by1, std::mt19937& rng) {
  std::vector<float> a(std::size_t(w) * std::size_t(h), 0.3f);
  std::bernoulli_distribution keep(0.6);
  for (int y = by0; y <= by1; ++y)
    for (int x = bx0; x <= bx1; ++x)
      if (keep(rng) || (x == bx0 && y == by0) || (x == bx1 && y == by1)) a[std::size_t(y) * w + x] = 0.9f;
  return a;
}

TEST(NetWindow, SurfaceBoundsGrownByTheRadiusAlignedAndClamped) {
  std::mt19937 rng(1);
  const std::vector<float> a = blob_alpha(64, 40, 21, 12, 30, 19, rng);
  const PixelWindow w = net_window(a.data(), 64, 40, 0.5f, 6);
  EXPECT_EQ(w.x0, 12);  // 21 - 6 = 15, down to a multiple of 4
  EXPECT_EQ(w.x1, 41);  // 30 + 1 + 6 + 4
  EXPECT_EQ(w.y0, 6);
  EXPECT_EQ(w.y1, 26);

  const std::vector<float> edge = blob_alpha(64, 40, 2, 0, 61, 38, rng);
  const PixelWindow c = net_window(edge.data(), 64, 40, 0.5f, 6);
  EXPECT_EQ(c.x0, 0);
  EXPECT_EQ(c.y0, 0);
  EXPECT_EQ(c.x1, 64);
  EXPECT_EQ(c.y1, 40);
  EXPECT_TRUE(c.covers(64, 40));

  const std::vector<float> none(64 * 40, 0.5f);  // at the threshold: not a surface pixel
  EXPECT_TRUE(net_window(none.data(), 64, 40, 0.5f, 6).empty());
}

template <class T>
struct NetRun {
  std::vector<T> rs, param_grads, input_grads;
};

// Forward and backward on the whole image or a window; dL/drs = upstream on surface pixels, 0 elsewhere (as
// the shading's backward gives it).
template <class T>
NetRun<T> run_net(const std::vector<T>& input, const std::vector<T>& upstream, int w, int h, const PixelWindow* win) {
  RoughnessNet<T> net(NetConfig{}, Device::CPU, 7);
  Buffer<T> in(input, Device::CPU), rs, g(upstream, Device::CPU), gin(input.size(), Device::CPU);
  gin.fill_zero();
  net.forward(in, h, w, rs, win);
  net.backward(g, &gin);
  return {rs.to_host(), net.grads().to_host(), gin.to_host()};
}

template <class T>
void expect_window_matches_whole_image() {
  std::mt19937 rng(3);
  const int w = 71, h = 45;
  const std::size_t hw = std::size_t(w) * h;
  const std::vector<float> alpha = blob_alpha(w, h, 23, 14, 47, 30, rng);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<T> input(3 * hw), upstream(hw, T(0));
  for (T& v : input) v = T(u(rng));
  for (std::size_t p = 0; p < hw; ++p)
    if (alpha[p] > 0.5f) upstream[p] = T(u(rng));

  RoughnessNet<T> probe(NetConfig{}, Device::CPU, 7);
  ASSERT_EQ(probe.receptive_radius(), 6);
  const PixelWindow win = net_window(alpha.data(), w, h, 0.5f, probe.receptive_radius());
  ASSERT_FALSE(win.covers(w, h));
  const NetRun<T> whole = run_net<T>(input, upstream, w, h, nullptr);
  const NetRun<T> part = run_net<T>(input, upstream, w, h, &win);
  std::size_t surface = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    if (!(alpha[p] > 0.5f)) continue;
    ++surface;
    ASSERT_EQ(part.rs[p], whole.rs[p]) << "pixel " << p;
  }
  EXPECT_GT(surface, 100u);
  for (std::size_t p = 0; p < hw; ++p) {
    const int x = int(p % std::size_t(w)), y = int(p / std::size_t(w));
    if (x < win.x0 || x >= win.x1 || y < win.y0 || y >= win.y1) ASSERT_EQ(part.rs[p], T(0)) << "pixel " << p;
  }
  ASSERT_EQ(part.param_grads.size(), whole.param_grads.size());
  for (std::size_t i = 0; i < whole.param_grads.size(); ++i)
    ASSERT_EQ(part.param_grads[i], whole.param_grads[i]) << "parameter " << i;
  for (std::size_t i = 0; i < whole.input_grads.size(); ++i)
    ASSERT_EQ(part.input_grads[i], whole.input_grads[i]) << "input " << i;

  // The next aligned start on the left, 4 pixels in: the surface's left edge loses part of its inputs.
  PixelWindow small = win;
  small.x0 = win.x0 + 4;
  const NetRun<T> cut = run_net<T>(input, upstream, w, h, &small);
  bool differs = false;
  for (std::size_t p = 0; p < hw; ++p) differs = differs || (alpha[p] > 0.5f && cut.rs[p] != whole.rs[p]);
  EXPECT_TRUE(differs);
}

TEST(NetWindow, FloatOutputAndGradientsEqualTheWholeImagesBitForBit) { expect_window_matches_whole_image<float>(); }
TEST(NetWindow, DoubleOutputAndGradientsEqualTheWholeImagesBitForBit) { expect_window_matches_whole_image<double>(); }

// The net keeps its layers' buffers from one call to the next (the window changes size from view to view): a
// window after the whole image and a smaller window gives what a fresh net gives.
TEST(NetWindow, BuffersKeptFromLargerCallsChangeNothing) {
  std::mt19937 rng(4);
  const int w = 64, h = 48;
  const std::size_t hw = std::size_t(w) * h;
  const std::vector<float> alpha = blob_alpha(w, h, 20, 10, 40, 30, rng);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> input(3 * hw), upstream(hw, 0.0f);
  for (float& v : input) v = u(rng);
  for (std::size_t p = 0; p < hw; ++p)
    if (alpha[p] > 0.5f) upstream[p] = u(rng);
  const PixelWindow win = net_window(alpha.data(), w, h, 0.5f, 6);
  const NetRun<float> fresh = run_net<float>(input, upstream, w, h, &win);

  RoughnessNet<float> net(NetConfig{}, Device::CPU, 7);
  Buffer<float> in(input, Device::CPU), rs, g(upstream, Device::CPU), gin(3 * hw, Device::CPU);
  const PixelWindow smaller{8, 8, 20, 20};
  for (const PixelWindow* first : {static_cast<const PixelWindow*>(nullptr), &smaller}) {
    gin.fill_zero();
    net.forward(in, h, w, rs, first);
    net.backward(g, &gin);
  }
  net.zero_grad();
  gin.fill_zero();
  net.forward(in, h, w, rs, &win);
  net.backward(g, &gin);
  EXPECT_EQ(rs.to_host(), fresh.rs);
  EXPECT_EQ(net.grads().to_host(), fresh.param_grads);
  EXPECT_EQ(gin.to_host(), fresh.input_grads);
}

TEST(NetWindow, AWindowOutsideTheImageThrows) {
  RoughnessNet<float> net(NetConfig{}, Device::CPU, 1);
  Buffer<float> in(std::vector<float>(3 * 16 * 16, 0.1f), Device::CPU), rs;
  const PixelWindow outside{8, 0, 20, 16};
  EXPECT_THROW(net.forward(in, 16, 16, rs, &outside), Error);
  const PixelWindow empty{4, 4, 4, 9};
  EXPECT_THROW(net.forward(in, 16, 16, rs, &empty), Error);
}

}  // namespace
}  // namespace goris::ssf
