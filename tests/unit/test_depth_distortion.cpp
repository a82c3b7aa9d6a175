// Depth distortion (train/losses/depth_distortion.h, train/radiance/depth_distortion_pass.h): the image-space
// identity A M2 - M1^2 = sum_{i<j} w_i w_j (m_i - m_j)^2, finite-difference gradients in double precision of
// each piece and of the whole composition through the rasterizer, the float pass against the double maths,
// and what the loss is for: two surfaces on one ray cost, one does not, and its gradient separates less.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/raster/raster_cpu.h"
#include "tests/unit/test_raster_scenes.h"
#include "train/losses/depth_distortion.h"
#include "train/radiance/depth_distortion_pass.h"

using namespace goris;
using goris::test::RasterScene;
using goris::test::SceneSpec;

namespace {

// Depths 3-5 map to m 0.67-0.80: differences large enough for tight finite differences.
const DistortionDepthRange kRange{1.0, 100.0};

// The loss of a double scene: moments of the centres as the two extra channels, rasterized, A M2 - M1^2.
double scene_loss(const RasterScene<double>& s, const Camera& cam, RasterScene<double>* grads = nullptr) {
  RasterScene<double> v = s;
  v.n_extras = 2;
  v.sh_degree = 0;
  v.extras.assign(2 * std::size_t(s.count), 0.0);
  const double center = distortion_center(v.positions.data(), std::size_t(v.count), cam, kRange);
  distortion_moments(v.positions.data(), std::size_t(v.count), cam, kRange, center, v.extras.data());
  GBufferT<double> gb;
  RasterStateT<double> st;
  raster::forward_cpu(v.view(), cam, RasterSettings::classic_3dgs(), gb, st);
  const std::size_t hw = gb.pixels();
  std::vector<double> gA(hw, 0.0), gM(2 * hw, 0.0);
  const double loss = depth_distortion_loss(gb.alpha.data(), gb.extras.data(), gb.extras.data() + hw, hw, gA.data(),
                                            gM.data(), gM.data() + hw, 1.0);
  if (grads) {
    const std::size_t n = std::size_t(s.count);
    grads->positions.assign(3 * n, 0.0);
    grads->log_scales.assign(3 * n, 0.0);
    grads->rotations.assign(4 * n, 0.0);
    grads->opacity_logits.assign(n, 0.0);
    std::vector<double> g_moments(2 * n, 0.0);
    GBufferGradT<double> go;
    go.alpha = gA.data();
    go.extras = gM.data();
    GaussianGradsT<double> out;
    out.positions = grads->positions.data();
    out.log_scales = grads->log_scales.data();
    out.rotations = grads->rotations.data();
    out.opacity_logits = grads->opacity_logits.data();
    out.extras = g_moments.data();
    raster::backward_cpu(v.view(), st, go, out);
    distortion_moments_backward(v.positions.data(), n, cam, kRange, center, g_moments.data(), grads->positions.data());
  }
  return loss;
}

// Central difference of f() in x[i] (x restored).
template <class F>
double central_difference(std::vector<double>& x, std::size_t i, F f, double eps = 1e-6) {
  const double x0 = x[i];
  x[i] = x0 + eps;
  const double lp = f();
  x[i] = x0 - eps;
  const double lm = f();
  x[i] = x0;
  return (lp - lm) / (2 * eps);
}

// A scene of overlapping Gaussians around the origin seen from distance 4 (some pixels blend several).
struct Case {
  RasterScene<double> scene;
  Camera camera;
};
Case make_case(std::uint32_t seed) {
  std::mt19937 rng(seed);
  SceneSpec spec;
  spec.count = 5;
  spec.sh_degree = 0;
  spec.n_extras = 0;
  return {goris::test::random_scene<double>(rng, spec), goris::test::random_camera(rng, 24, 20, 30.f, 4.f)};
}

}  // namespace

TEST(DepthDistortion, ImageLossEqualsThePairSum) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double T = 1, A = 0, M1 = 0, M2 = 0, pairs = 0;
  std::vector<double> w, m;
  for (int i = 0; i < 6; ++i) {
    const double a = 0.1 + 0.6 * u(rng), mi = u(rng);
    for (std::size_t j = 0; j < w.size(); ++j) pairs += a * T * w[j] * (mi - m[j]) * (mi - m[j]);
    w.push_back(a * T);
    m.push_back(mi);
    A += a * T, M1 += a * T * mi, M2 += a * T * mi * mi;
    T *= 1 - a;
  }
  EXPECT_NEAR(depth_distortion_loss(&A, &M1, &M2, 1, (double*)nullptr, (double*)nullptr, (double*)nullptr, 1.0),
              pairs, 1e-12);
}

TEST(DepthDistortion, ImageLossGradientMatchesFiniteDifferences) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t hw = 7;
  std::vector<double> img(3 * hw);
  for (std::size_t p = 0; p < hw; ++p) {  // consistent moments: A M2 >= M1^2
    img[p] = 0.2 + 0.7 * u(rng);
    img[hw + p] = img[p] * u(rng);
    img[2 * hw + p] = img[hw + p] * img[hw + p] / img[p] + 0.3 * u(rng);
  }
  const double weight = 2.5;
  std::vector<double> pixel_weight(hw);
  for (double& w : pixel_weight) w = u(rng);
  const std::vector<const double*> weightings{nullptr, pixel_weight.data()};  // uniform, then per pixel
  for (const double* pw : weightings) {
    std::vector<double> g(3 * hw, 0.0);
    depth_distortion_loss(img.data(), img.data() + hw, img.data() + 2 * hw, hw, g.data(), g.data() + hw,
                          g.data() + 2 * hw, weight, pw);
    auto L = [&] {
      return weight * depth_distortion_loss(img.data(), img.data() + hw, img.data() + 2 * hw, hw, (double*)nullptr,
                                            (double*)nullptr, (double*)nullptr, 1.0, pw);
    };
    for (std::size_t i = 0; i < img.size(); ++i) EXPECT_NEAR(g[i], central_difference(img, i, L), 1e-7) << i;
  }
  // A zero weight on a pixel removes it from the loss.
  std::vector<double> only_first(hw, 0.0);
  only_first[0] = 1.0;
  EXPECT_NEAR(depth_distortion_loss(img.data(), img.data() + hw, img.data() + 2 * hw, hw, (double*)nullptr,
                                    (double*)nullptr, (double*)nullptr, 1.0, only_first.data()),
              (img[0] * img[2 * hw] - img[hw] * img[hw]) / double(hw), 1e-12);
}

TEST(DepthDistortion, MomentsBackwardMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  const Case c = make_case(7);
  std::vector<double> pos = c.scene.positions, gm(2 * std::size_t(c.scene.count));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& x : gm) x = u(rng);
  const std::size_t n = std::size_t(c.scene.count);
  std::vector<double> g(3 * n, 0.0), mom(2 * n);
  const double center = 0.7;
  distortion_moments_backward(pos.data(), n, c.camera, kRange, center, gm.data(), g.data());
  auto L = [&] {
    distortion_moments(pos.data(), n, c.camera, kRange, center, mom.data());
    double l = 0;
    for (std::size_t k = 0; k < mom.size(); ++k) l += gm[k] * mom[k];
    return l;
  };
  for (std::size_t i = 0; i < pos.size(); ++i) EXPECT_NEAR(g[i], central_difference(pos, i, L), 1e-7) << i;
}

TEST(DepthDistortion, ThroughTheRasterizerMatchesFiniteDifferences) {
  for (std::uint32_t seed : {11u, 12u}) {
    Case c = make_case(seed);
    RasterScene<double> g;
    const double loss = scene_loss(c.scene, c.camera, &g);
    ASSERT_GT(loss, 1e-9) << "the case must overlap Gaussians at different depths";
    auto check = [&](std::vector<double> RasterScene<double>::*field, const char* name) {
      std::vector<double>& x = c.scene.*field;
      const std::vector<double>& an = g.*field;
      double scale = 1e-12;
      std::vector<double> num(x.size());
      for (std::size_t i = 0; i < x.size(); ++i) {
        num[i] = central_difference(x, i, [&] { return scene_loss(c.scene, c.camera); });
        scale = std::max({scale, std::abs(num[i]), std::abs(an[i])});
      }
      for (std::size_t i = 0; i < x.size(); ++i)
        EXPECT_NEAR(an[i], num[i], 2e-6 * scale + 1e-5 * std::abs(num[i])) << name << "[" << i << "] seed " << seed;
    };
    check(&RasterScene<double>::positions, "positions");
    check(&RasterScene<double>::log_scales, "log_scales");
    check(&RasterScene<double>::rotations, "rotations");
    check(&RasterScene<double>::opacity_logits, "opacity_logits");
  }
}

// The production pass (float, through rasterize / rasterize_backward) computes the double maths above.
TEST(DepthDistortion, FloatPassMatchesTheDoubleMaths) {
  const Case c = make_case(11);
  RasterScene<double> gd;
  const double loss_d = scene_loss(c.scene, c.camera, &gd);
  auto to_f = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
  const std::vector<float> pos = to_f(c.scene.positions), ls = to_f(c.scene.log_scales), rot = to_f(c.scene.rotations),
                           op = to_f(c.scene.opacity_logits), sh = to_f(c.scene.sh);
  GaussianView v;
  v.count = c.scene.count;
  v.positions = pos.data(), v.log_scales = ls.data(), v.rotations = rot.data(), v.opacity_logits = op.data();
  v.sh = sh.data();
  const std::size_t n = std::size_t(c.scene.count);
  std::vector<float> gp(3 * n, 0.f), gs(3 * n, 0.f), gr(4 * n, 0.f), go(n, 0.f);
  GaussianGradView g;
  g.positions = gp.data(), g.log_scales = gs.data(), g.rotations = gr.data(), g.opacity_logits = go.data();
  const float weight = 3.0f;
  const double loss_f =
      depth_distortion_pass(v, c.camera, RasterSettings::classic_3dgs(), kRange, weight, nullptr, g, Device::CPU);
  EXPECT_NEAR(loss_f, loss_d, 1e-4 * loss_d + 1e-9);
  auto close = [&](const std::vector<float>& f, const std::vector<double>& d, const char* name) {
    double scale = 1e-12;
    for (double x : d) scale = std::max(scale, std::abs(weight * x));
    for (std::size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(f[i], weight * d[i], 2e-3 * scale) << name << "[" << i << "]";
  };
  close(gp, gd.positions, "positions");
  close(gs, gd.log_scales, "log_scales");
  close(gr, gd.rotations, "rotations");
  close(go, gd.opacity_logits, "opacity_logits");
}

// A half-transparent surface in front of another (the mirror world behind a glossy table) costs; either one
// alone does not; and stepping down the gradient pulls the two together.
TEST(DepthDistortion, TwoSurfacesOnOneRayCostAndTheGradientPullsThemTogether) {
  Camera cam;
  cam.width = cam.height = 16;
  cam.fx = cam.fy = 20.f;
  cam.cx = cam.cy = 8.f;
  cam.t = glm::vec3(0.f, 0.f, 4.f);  // looking down +z at the origin from z = -4
  // Two broad, flat-on discs on the optical axis, 0.5 apart.
  std::vector<float> pos = {0.f, 0.f, -0.25f, 0.f, 0.f, 0.25f}, ls(6, std::log(0.6f)), rot = {1, 0, 0, 0, 1, 0, 0, 0},
                     op = {0.f, 2.f}, sh(2 * 48, 0.f);
  for (int i = 0; i < 2; ++i) ls[3 * i + 2] = std::log(0.02f);
  GaussianView v;
  v.count = 2;
  v.positions = pos.data(), v.log_scales = ls.data(), v.rotations = rot.data(), v.opacity_logits = op.data();
  v.sh = sh.data();
  auto run = [&](GaussianGradView g, float weight) {
    return depth_distortion_pass(v, cam, RasterSettings::classic_3dgs(), kRange, weight, nullptr, g, Device::CPU);
  };
  const double both = run({}, 0.f);
  EXPECT_GT(both, 1e-6);
  v.count = 1;  // the front disc alone
  EXPECT_LT(run({}, 0.f), 1e-3 * both);
  v.count = 2;

  std::vector<float> gp(6, 0.f);
  GaussianGradView g;
  g.positions = gp.data();
  run(g, 1.f);
  EXPECT_LT(gp[2], 0.f) << "descent moves the front disc back (+z)";
  EXPECT_GT(gp[5], 0.f) << "descent moves the back disc forward (-z)";
  for (int i = 0; i < 6; ++i) pos[i] -= 0.05f * float(gp[i] / std::max(std::abs(gp[2]), std::abs(gp[5])));
  EXPECT_LT(run({}, 0.f), both);
}
