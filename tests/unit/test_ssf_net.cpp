// Roughness net (render/ssf/roughness_net.h) and its layers (conv_passes.h): finite-difference gradients in
// double for each layer and the whole net, the row (CPU) and pixel (CUDA) kernel forms agreeing, He
// initialisation, the Adam hook, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "core/util/error.h"
#include "render/ssf/conv_passes.h"
#include "train/optimizer/flat_adam.h"
#include "render/ssf/roughness_net.h"

namespace goris::ssf {
namespace {

std::vector<double> random_vec(std::size_t n, std::mt19937& rng, double lo = -1.0, double hi = 1.0) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (double& x : v) x = u(rng);
  return v;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// Checks analytic[i] against central differences of f around v[i] for every i.
void expect_fd(std::vector<double>& v, const std::function<double()>& f, const std::vector<double>& analytic,
               const char* what, double tol = 1e-7) {
  ASSERT_EQ(v.size(), analytic.size());
  const double h = 1e-6;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double keep = v[i];
    v[i] = keep + h;
    const double lp = f();
    v[i] = keep - h;
    const double lm = f();
    v[i] = keep;
    const double fd = (lp - lm) / (2 * h);
    ASSERT_NEAR(analytic[i], fd, tol * (1 + std::abs(fd))) << what << " " << i;
  }
}

// (kernel size, input channels, output channels): multiples of 8 take the CPU's register-blocked kernels.
class ConvLayer : public ::testing::TestWithParam<std::tuple<int, int, int>> {
 protected:
  ConvShape shape(int h, int w) const {
    return ConvShape{std::get<1>(GetParam()), std::get<2>(GetParam()), std::get<0>(GetParam()), h, w};
  }
};

TEST_P(ConvLayer, GradientsMatchFiniteDifferences) {
  std::mt19937 rng(10 + std::get<0>(GetParam()) + std::get<1>(GetParam()));
  const ConvShape s = shape(5, 19);  // wide enough for two 8-pixel blocks and a remainder
  std::vector<double> in = random_vec(std::size_t(s.cin) * s.plane(), rng);
  std::vector<double> w = random_vec(std::size_t(s.weight_count()), rng);
  std::vector<double> b = random_vec(std::size_t(s.cout), rng);
  const std::vector<double> g_out = random_vec(std::size_t(s.cout) * s.plane(), rng);
  std::vector<double> out(g_out.size());
  auto loss = [&] {
    conv_forward<Device::CPU>(s, in.data(), w.data(), b.data(), out.data());
    return dot(out, g_out);
  };
  std::vector<double> g_in(in.size()), g_w(w.size(), 0.0), g_b(b.size(), 0.0);
  std::vector<double> partials(std::size_t(s.h) * (w.size() + b.size()));
  conv_backward_input<Device::CPU>(s, w.data(), g_out.data(), g_in.data());
  conv_backward_params<Device::CPU>(s, in.data(), g_out.data(), partials.data(), g_w.data(), g_b.data());
  expect_fd(in, loss, g_in, "input");
  expect_fd(w, loss, g_w, "weight");
  expect_fd(b, loss, g_b, "bias");
}

// The CPU passes (row or blocked kernels) against the per-pixel kernels the CUDA backend runs.
TEST_P(ConvLayer, CpuPassesAgreeWithPerPixelKernels) {
  std::mt19937 rng(20 + std::get<0>(GetParam()) + std::get<2>(GetParam()));
  const ConvShape s = shape(6, 21);
  const std::vector<double> in = random_vec(std::size_t(s.cin) * s.plane(), rng);
  const std::vector<double> w = random_vec(std::size_t(s.weight_count()), rng);
  const std::vector<double> b = random_vec(std::size_t(s.cout), rng);
  const std::vector<double> g_out = random_vec(std::size_t(s.cout) * s.plane(), rng);
  std::vector<double> cpu(g_out.size()), pix(g_out.size()), gi_cpu(in.size()), gi_pix(in.size());
  std::vector<double> gw(w.size(), 0.0), gb(b.size(), 0.0), partials(std::size_t(s.h) * (w.size() + b.size()));
  conv_forward<Device::CPU>(s, in.data(), w.data(), b.data(), cpu.data());
  conv_backward_input<Device::CPU>(s, w.data(), g_out.data(), gi_cpu.data());
  conv_backward_params<Device::CPU>(s, in.data(), g_out.data(), partials.data(), gw.data(), gb.data());
  for (int y = 0; y < s.h; ++y)
    for (int x = 0; x < s.w; ++x) {
      conv_forward_pixel(s, in.data(), w.data(), b.data(), pix.data(), y, x);
      conv_grad_input_pixel(s, w.data(), g_out.data(), gi_pix.data(), y, x);
    }
  for (std::size_t i = 0; i < cpu.size(); ++i) ASSERT_NEAR(cpu[i], pix[i], 1e-12);
  for (std::size_t i = 0; i < gi_cpu.size(); ++i) ASSERT_NEAR(gi_cpu[i], gi_pix[i], 1e-12);
  const int np = s.weight_count() + s.cout;
  for (int p = 0; p < np; ++p) {
    double ref = 0;
    for (int y = 0; y < s.h; ++y) ref += conv_param_grad_row(s, in.data(), g_out.data(), p, y);
    ASSERT_NEAR(p < s.weight_count() ? gw[std::size_t(p)] : gb[std::size_t(p - s.weight_count())], ref, 1e-11) << p;
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, ConvLayer,
                         ::testing::Values(std::make_tuple(1, 3, 5), std::make_tuple(3, 3, 5), std::make_tuple(1, 3, 8),
                                           std::make_tuple(3, 8, 16), std::make_tuple(3, 16, 8),
                                           std::make_tuple(1, 8, 1), std::make_tuple(3, 8, 1)));

TEST(SsfActivations, GradientsMatchFiniteDifferences) {
  std::mt19937 rng(30);
  std::vector<double> z = random_vec(50, rng, -3.0, 3.0);
  for (double& v : z)
    if (std::abs(v) < 1e-3) v = 0.5;  // keep away from the ReLU kink
  const std::vector<double> g = random_vec(z.size(), rng);
  std::vector<double> y(z.size());
  auto relu_loss = [&] {
    y = z;
    relu_forward<Device::CPU>(y.data(), y.size());
    return dot(y, g);
  };
  auto sigmoid_loss = [&] {
    sigmoid_forward<Device::CPU>(z.data(), y.data(), y.size());
    return dot(y, g);
  };
  relu_loss();
  std::vector<double> a = g;
  relu_backward<Device::CPU>(y.data(), a.data(), a.size());
  expect_fd(z, relu_loss, a, "relu");
  sigmoid_loss();
  a = g;
  sigmoid_backward<Device::CPU>(y.data(), a.data(), a.size());
  expect_fd(z, sigmoid_loss, a, "sigmoid");
}

// The net's parameters with every zero replaced by zero_fill(i) (biases and a zero-started output layer
// then take part), its gradients of L = dot(R_s, g_rs) after one backward(), and R_s at those parameters.
struct NetGradients {
  std::vector<double> params, g_params, rs;
};

// Checks the gradients to the parameters and to `in` against central differences of L.
NetGradients expect_net_gradients(RoughnessNet<double>& net, std::vector<double> in, int H, int W,
                                  const std::vector<double>& g_rs, double (*zero_fill)(std::size_t)) {
  NetGradients out;
  out.params = net.params().to_host();
  for (std::size_t i = 0; i < out.params.size(); ++i)
    if (out.params[i] == 0.0) out.params[i] = zero_fill(i);
  Buffer<double> rs;
  auto loss = [&] {
    net.params().upload(out.params.data(), out.params.size());
    net.forward(Buffer<double>(in, Device::CPU), H, W, rs);
    return dot(rs.to_host(), g_rs);
  };
  loss();
  out.rs = rs.to_host();
  net.zero_grad();
  Buffer<double> g_in(std::vector<double>(in.size(), 0.0), Device::CPU);
  net.backward(Buffer<double>(g_rs, Device::CPU), &g_in);
  out.g_params = net.grads().to_host();
  const std::vector<double> g_input = g_in.to_host();
  expect_fd(out.params, loss, out.g_params, "parameter", 1e-6);
  expect_fd(in, loss, g_input, "input", 1e-6);
  net.params().upload(out.params.data(), out.params.size());
  net.forward(Buffer<double>(in, Device::CPU), H, W, rs);  // back at the unperturbed point
  return out;
}

TEST(SsfNet, WholeNetGradientsMatchFiniteDifferences) {
  const NetConfig cfg{3, 8, 2};
  const int H = 7, W = 6;
  const std::size_t plane = std::size_t(H) * W;
  RoughnessNet<double> net(cfg, Device::CPU, 42);
  std::mt19937 rng(31);
  const std::vector<double> in = random_vec(3 * plane, rng, 0.0, 2.0);
  const std::vector<double> g_rs = random_vec(plane, rng);
  // Biases start at zero: make them exercise the ReLUs too.
  const NetGradients g = expect_net_gradients(net, in, H, W, g_rs, [](std::size_t i) { return 0.05 * double(i % 7) - 0.1; });
  for (double r : g.rs) {
    EXPECT_GT(r, 0.0);
    EXPECT_LT(r, 1.0);
  }
  // backward() adds: a second call doubles the parameter gradients.
  net.backward(Buffer<double>(g_rs, Device::CPU), nullptr);
  const std::vector<double> twice = net.grads().to_host();
  for (std::size_t i = 0; i < twice.size(); ++i)
    ASSERT_NEAR(twice[i], 2 * g.g_params[i], 1e-12 * (1 + std::abs(g.g_params[i])));
}

TEST(SsfNet, HeInitialisationIsSeededAndScaled) {
  const NetConfig cfg;  // 3 -> 8, 6 x 3x3, 8 -> 1
  RoughnessNet<float> a(cfg, Device::CPU, 7), b(cfg, Device::CPU, 7), c(cfg, Device::CPU, 8);
  EXPECT_EQ(a.layer_count(), 8);
  EXPECT_EQ(a.param_count(), std::size_t(3 * 8 + 8 + 6 * (8 * 8 * 9 + 8) + 8 + 1));
  const std::vector<float> pa = a.params().to_host(), pb = b.params().to_host(), pc = c.params().to_host();
  EXPECT_EQ(pa, pb);
  EXPECT_NE(pa, pc);
  double sum2 = 0;
  std::size_t count = 0;
  for (int l = 1; l <= 6; ++l) {
    const std::size_t off = a.weight_offset(l);
    for (std::size_t i = 0; i < 8 * 8 * 9; ++i, ++count) sum2 += double(pa[off + i]) * pa[off + i];
    for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(pa[off + 8 * 8 * 9 + i], 0.0f);  // biases
  }
  EXPECT_NEAR(std::sqrt(sum2 / double(count)), std::sqrt(2.0 / 72.0), 0.1 * std::sqrt(2.0 / 72.0));
}

TEST(SsfNet, AdamStepMovesEveryParameterAgainstItsGradient) {
  RoughnessNet<float> net(NetConfig{}, Device::CPU, 3);
  FlatAdam adam(net.param_count(), net.device());
  const std::vector<float> before = net.params().to_host();
  std::vector<float> g(before.size());
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = (i % 2 ? 1.0f : -2.0f) * float(1 + i % 5);
  net.grads().upload(g.data(), g.size());
  adam.step(net.params(), net.grads(), 1e-3f, "roughness net");
  EXPECT_EQ(adam.steps(), 1);
  const std::vector<float> after = net.params().to_host();
  // Adam's first bias-corrected step is lr * sign(g).
  for (std::size_t i = 0; i < g.size(); ++i) ASSERT_NEAR(after[i] - before[i], g[i] > 0 ? -1e-3f : 1e-3f, 1e-6f) << i;
}

TEST(SsfNet, BadInputThrows) {
  RoughnessNet<float> net(NetConfig{}, Device::CPU, 1);
  const int H = 4, W = 5;
  Buffer<float> rs;
  std::vector<float> in(3 * H * W, 0.5f);
  EXPECT_THROW(net.backward(Buffer<float>(std::vector<float>(H * W), Device::CPU), nullptr), Error);
  EXPECT_THROW(net.forward(Buffer<float>(std::vector<float>(2 * H * W), Device::CPU), H, W, rs), Error);
  EXPECT_THROW(net.forward(Buffer<float>(in, Device::CPU), 0, W, rs), Error);
  in[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(net.forward(Buffer<float>(in, Device::CPU), H, W, rs), Error);
  in[3] = 0.5f;
  net.forward(Buffer<float>(in, Device::CPU), H, W, rs);
  EXPECT_THROW(net.backward(Buffer<float>(std::vector<float>(H * W + 1), Device::CPU), nullptr), Error);
  EXPECT_THROW(RoughnessNet<float>(NetConfig{0, 8, 6}, Device::CPU, 1), Error);
  EXPECT_THROW(RoughnessNet<float>(NetConfig{3, kMaxConvChannels + 1, 6}, Device::CPU, 1), Error);
}

}  // namespace
}  // namespace goris::ssf
