// Finite-difference checks of the rasterizer's backward pass in double precision: every parameter group
// against every G-buffer channel, on small random scenes and cameras. The loss is a random linear function
// of one channel, L = sum_p w_p out_p; analytic dL/dparam is compared with central differences. Scenes keep
// alpha below 0.99 and T above 1e-4, so no threshold flips under the small perturbation.
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "render/raster/raster_cpu.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_raster_scenes.h"

using namespace goris;
using goris::test::RasterScene;
using goris::test::SceneSpec;

namespace {

enum class Channel { Color, Alpha, Depth, Median, Normal, Extras };
const Channel kChannels[] = {Channel::Color, Channel::Alpha, Channel::Depth, Channel::Median, Channel::Normal,
                             Channel::Extras};
const char* channel_name(Channel c) {
  switch (c) {
    case Channel::Color: return "color";
    case Channel::Alpha: return "alpha";
    case Channel::Depth: return "depth";
    case Channel::Median: return "median_depth";
    case Channel::Normal: return "normal";
    case Channel::Extras: return "extras";
  }
  return "?";
}

struct Case {
  RasterScene<double> scene;
  Camera camera;
  RasterSettings settings;
};

// Loss weights for one channel (other channels zero).
struct Weights {
  Channel ch;
  std::vector<double> w;
};

Weights make_weights(Channel ch, const Case& c, std::mt19937& rng) {
  const std::size_t P = std::size_t(c.camera.width) * c.camera.height;
  const std::size_t n = ch == Channel::Color || ch == Channel::Normal ? 3 * P
                        : ch == Channel::Extras                      ? std::size_t(c.scene.n_extras) * P
                                                                     : P;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Weights w{ch, std::vector<double>(n)};
  for (auto& x : w.w) x = u(rng);
  return w;
}

const Buffer<double>& channel_of(const GBufferT<double>& gb, Channel ch) {
  switch (ch) {
    case Channel::Color: return gb.color;
    case Channel::Alpha: return gb.alpha;
    case Channel::Depth: return gb.depth;
    case Channel::Median: return gb.median_depth;
    case Channel::Normal: return gb.normal;
    case Channel::Extras: return gb.extras;
  }
  return gb.color;
}

double loss(const Case& c, const Weights& w) {
  GBufferT<double> gb;
  RasterStateT<double> st;
  raster::forward_cpu(c.scene.view(), c.camera, c.settings, gb, st);
  const Buffer<double>& out = channel_of(gb, w.ch);
  double l = 0;
  for (std::size_t i = 0; i < w.w.size(); ++i) l += w.w[i] * out[i];
  return l;
}

struct Grads {
  std::vector<double> positions, log_scales, rotations, opacity_logits, sh, extras, mean2d_norm;
};

Grads analytic(const Case& c, const Weights& w) {
  GBufferT<double> gb;
  RasterStateT<double> st;
  raster::forward_cpu(c.scene.view(), c.camera, c.settings, gb, st);
  GBufferGradT<double> go;
  const double* p = w.w.data();
  switch (w.ch) {
    case Channel::Color: go.color = p; break;
    case Channel::Alpha: go.alpha = p; break;
    case Channel::Depth: go.depth = p; break;
    case Channel::Median: go.median_depth = p; break;
    case Channel::Normal: go.normal = p; break;
    case Channel::Extras: go.extras = p; break;
  }
  const int n = c.scene.count;
  Grads g{std::vector<double>(3 * n), std::vector<double>(3 * n), std::vector<double>(4 * n),
          std::vector<double>(n),     std::vector<double>(48 * n), std::vector<double>(c.scene.extras.size()),
          std::vector<double>(n)};
  GaussianGradsT<double> out{g.positions.data(), g.log_scales.data(), g.rotations.data(), g.opacity_logits.data(),
                             g.sh.data(),        g.extras.data(),     g.mean2d_norm.data()};
  raster::backward_cpu(c.scene.view(), st, go, out);
  return g;
}

// Compares the first n_used entries of one parameter group with central differences.
void check_group(Case c, const Weights& w, const std::string& group, std::vector<double> RasterScene<double>::*field,
                 const std::vector<double>& grad, std::size_t n_used) {
  const double eps = 1e-6;
  std::vector<double> num(n_used);
  for (std::size_t i = 0; i < n_used; ++i) {
    const double x0 = (c.scene.*field)[i];
    (c.scene.*field)[i] = x0 + eps;
    const double lp = loss(c, w);
    (c.scene.*field)[i] = x0 - eps;
    const double lm = loss(c, w);
    (c.scene.*field)[i] = x0;
    num[i] = (lp - lm) / (2 * eps);
  }
  double scale = 1e-12;
  for (std::size_t i = 0; i < n_used; ++i) scale = std::max({scale, std::abs(num[i]), std::abs(grad[i])});
  for (std::size_t i = 0; i < n_used; ++i)
    EXPECT_NEAR(grad[i], num[i], 2e-6 * scale + 1e-5 * std::abs(num[i]))
        << group << "[" << i << "] vs channel " << channel_name(w.ch) << " (scale " << scale << ")";
}

void check_all(const Case& c, std::mt19937& rng) {
  for (Channel ch : kChannels) {
    if (ch == Channel::Extras && c.scene.n_extras == 0) continue;
    const Weights w = make_weights(ch, c, rng);
    const Grads g = analytic(c, w);
    const std::size_t n = std::size_t(c.scene.count);
    check_group(c, w, "positions", &RasterScene<double>::positions, g.positions, 3 * n);
    check_group(c, w, "log_scales", &RasterScene<double>::log_scales, g.log_scales, 3 * n);
    check_group(c, w, "rotations", &RasterScene<double>::rotations, g.rotations, 4 * n);
    check_group(c, w, "opacity_logits", &RasterScene<double>::opacity_logits, g.opacity_logits, n);
    check_group(c, w, "sh", &RasterScene<double>::sh, g.sh, 48 * n);
    if (c.scene.n_extras > 0)
      check_group(c, w, "extras", &RasterScene<double>::extras, g.extras, std::size_t(c.scene.n_extras) * n);
  }
}

// Draws a scene whose rendered result is non-trivial: every Gaussian visible and some overlap.
Case make_case(std::mt19937& rng, const SceneSpec& spec, const RasterSettings& settings) {
  for (;;) {
    Case c{goris::test::random_scene<double>(rng, spec), goris::test::random_camera(rng, 24, 20, 30.f, 4.f),
           settings};
    GBufferT<double> gb;
    RasterStateT<double> st;
    raster::forward_cpu(c.scene.view(), c.camera, c.settings, gb, st);
    bool all_visible = true;
    for (int i = 0; i < c.scene.count; ++i) all_visible = all_visible && st.radii[i] > 0;
    double min_T = 1;
    for (std::size_t p = 0; p < gb.pixels(); ++p) min_T = std::min(min_T, st.final_T[p]);
    if (all_visible && min_T < 0.6 && min_T > 1e-3) return c;
  }
}

}  // namespace

TEST(RasterGradients, AllChannelsAllParameters) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    SceneSpec spec;
    spec.sh_degree = trial + 1;
    check_all(make_case(rng, spec, RasterSettings::classic_3dgs()), rng);
  }
}

TEST(RasterGradients, MipSplattingFilters) {
  std::mt19937 rng(23);
  SceneSpec spec;
  spec.filter3d = true;
  spec.scale_lo = 0.05f;  // small enough that the 3D filter matters
  RasterSettings s = RasterSettings::mip_splatting();
  s.background = glm::vec3(0.3f, 0.6f, 0.9f);
  check_all(make_case(rng, spec, s), rng);
}

TEST(RasterGradients, ShDegreeZeroNoExtras) {
  std::mt19937 rng(5);
  SceneSpec spec;
  spec.sh_degree = 0;
  spec.n_extras = 0;
  spec.count = 4;
  check_all(make_case(rng, spec, RasterSettings::classic_3dgs()), rng);
}

// A large Gaussian whose centre lies beyond the frustum clamp (x/z > 1.3 tan(fov/2)) but whose footprint
// reaches the image: the clamped Jacobian's gradient is exact too.
TEST(RasterGradients, ClampedJacobian) {
  std::mt19937 rng(3);
  SceneSpec spec;
  spec.count = 1;
  spec.scale_lo = 0.5f;
  spec.scale_hi = 0.6f;
  Case c{goris::test::random_scene<double>(rng, spec), Camera{}, RasterSettings::classic_3dgs()};
  c.camera.width = 24;
  c.camera.height = 20;
  c.camera.fx = c.camera.fy = 30.f;
  c.camera.cx = 12.f;
  c.camera.cy = 10.f;
  c.scene.positions = {2.4, 0.2, 4.0};  // x/z = 0.6, beyond the clamp at 1.3 * 12 / 30 = 0.52
  GBufferT<double> gb;
  RasterStateT<double> st;
  raster::forward_cpu(c.scene.view(), c.camera, c.settings, gb, st);
  ASSERT_GT(st.radii[0], 0) << "the test Gaussian must reach the image";
  ASSERT_GT(st.means2d[0], 24.0 + 0.15 * 24.0) << "the test Gaussian's centre must lie beyond the clamp";
  check_all(c, rng);
}
