// Finite-difference checks of the tracer's backward pass in double precision: every parameter group (position,
// log-scale, rotation, opacity logit, SH, extras, emit weight) and the ray origins and directions, through the
// library's own rounds (brute-force collector, so the test is about the maths, not the BVH). The loss is a
// random linear function of every output channel. Scenes are redrawn until no hit sits near a threshold
// (1/255, the 0.99 clamp, t_min, the 1e-4 stop, a colour clamp) and no two hits are nearly tied in t*.
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "render/trace/trace_cpu.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_trace_scenes.h"

using namespace goris;
using namespace goris::test;
namespace tr = goris::trace;

namespace {

using Scene = SceneArrays<double>;
using Rays = TraceRaySet<double>;

struct Weights {
  std::vector<double> color, depth, alpha, extras;
};

struct Case {
  Scene scene;
  Rays rays;
  Weights w;
  int k = 64;
};

tr::TraceScene<double> lib_scene(const Scene& s, const std::vector<tr::TracePrim<double>>& prims) {
  tr::TraceScene<double> sc;
  sc.count = s.count;
  sc.prims = prims.data();
  sc.sh = s.sh.data();
  sc.sh_degree = s.sh_degree;
  sc.extras = s.n_extras ? s.extras.data() : nullptr;
  sc.n_extras = s.n_extras;
  sc.emit = s.emit_or_null();
  return sc;
}

double loss(const Case& c) {
  const auto prims = tr::make_prims_cpu(c.scene.view(), nullptr, nullptr);
  const auto sc = lib_scene(c.scene, prims);
  const std::size_t n = c.rays.count();
  std::vector<double> color(3 * n), depth(n), alpha(n), extras(std::size_t(c.scene.n_extras) * n);
  TraceOutputsT<double> out{color.data(), depth.data(), alpha.data(), extras.data(), nullptr};
  tr::forward_cpu(sc, c.rays.view(), c.k, out, [&] { return tr::BruteForceCollector<double>{prims.data(), sc.count}; });
  double L = 0;
  for (std::size_t i = 0; i < color.size(); ++i) L += c.w.color[i] * color[i];
  for (std::size_t i = 0; i < n; ++i) L += c.w.depth[i] * depth[i] + c.w.alpha[i] * alpha[i];
  for (std::size_t i = 0; i < extras.size(); ++i) L += c.w.extras[i] * extras[i];
  return L;
}

struct Grads {
  std::vector<double> positions, log_scales, rotations, logits, sh, extras, emit, origins, directions;
};

Grads analytic(const Case& c) {
  const auto g = c.scene.view();
  const auto prims = tr::make_prims_cpu(g, nullptr, nullptr);
  const auto sc = lib_scene(c.scene, prims);
  const std::size_t N = std::size_t(c.scene.count), n = c.rays.count();
  Grads r{std::vector<double>(3 * N), std::vector<double>(3 * N), std::vector<double>(4 * N), std::vector<double>(N),
          std::vector<double>(48 * N), std::vector<double>(c.scene.extras.size()), std::vector<double>(N),
          std::vector<double>(3 * n), std::vector<double>(3 * n)};
  GaussianGradsT<double> gg;
  gg.positions = r.positions.data();
  gg.log_scales = r.log_scales.data();
  gg.rotations = r.rotations.data();
  gg.opacity_logits = r.logits.data();
  gg.sh = r.sh.data();
  gg.extras = r.extras.data();
  const TraceOutputGradsT<double> up{c.w.color.data(), c.w.depth.data(), c.w.alpha.data(), c.w.extras.data()};
  tr::backward_cpu(sc, g, c.rays.view(), c.k, up, gg, TraceRayGradsT<double>{r.origins.data(), r.directions.data()},
                   c.scene.emit.empty() ? nullptr : r.emit.data(), std::size_t(1) << 30,
                   [&] { return tr::BruteForceCollector<double>{prims.data(), sc.count}; });
  return r;
}

// True when every candidate hit is far from every threshold the finite differences could cross.
bool far_from_thresholds(const Case& c) {
  using V = gmath::Vec3<double>;
  const auto prims = tr::make_prims_cpu(c.scene.view(), nullptr, nullptr);
  int total_hits = 0;
  for (std::size_t r = 0; r < c.rays.count(); ++r) {
    const V o(c.rays.origins[3 * r], c.rays.origins[3 * r + 1], c.rays.origins[3 * r + 2]);
    const V d(c.rays.directions[3 * r], c.rays.directions[3 * r + 1], c.rays.directions[3 * r + 2]);
    std::vector<std::pair<double, int>> hits;
    for (int i = 0; i < c.scene.count; ++i) {
      const auto& p = prims[i];
      const auto M = tr::prim_matrix(p);
      const V a = M * (o - V(p.mean[0], p.mean[1], p.mean[2]));
      const V b = M * d;
      const double t = -glm::dot(a, b) / glm::dot(b, b);
      const V q = a + t * b;
      const double A = p.opacity * std::exp(-0.5 * glm::dot(q, q));
      if (std::abs(A - 1.0 / 255) < 1e-3 / 255 || std::abs(A - 0.99) < 1e-3 || std::abs(t - c.rays.t_min) < 1e-3)
        return false;
      if (A >= 1.0 / 255 && t > c.rays.t_min) hits.emplace_back(t, i);
    }
    std::sort(hits.begin(), hits.end());
    double trans = 1;
    for (std::size_t j = 0; j < hits.size(); ++j) {
      if (j > 0 && hits[j].first - hits[j - 1].first < 1e-4) return false;
      tr::HitEval<double> h;
      tr::eval_hit(prims[hits[j].second], o, d, c.rays.t_min, h);
      const double next = trans * (1 - h.alpha);
      if (std::abs(next - 1e-4) < 1e-3 * 1e-4) return false;
      if (next < 1e-4) break;
      const double* sh = &c.scene.sh[48 * std::size_t(hits[j].second)];
      double basis[16];
      gmath::sh_basis<double>(c.scene.sh_degree, glm::normalize(d), basis, nullptr);
      for (int ch = 0; ch < 3; ++ch) {
        double col = 0.5;
        for (int k = 0; k < gmath::sh_coeff_count(c.scene.sh_degree); ++k) col += basis[k] * sh[3 * k + ch];
        if (std::abs(col) < 1e-4) return false;
      }
      trans = next;
      ++total_hits;
    }
  }
  return total_hits >= int(c.rays.count());
}

Case make_case(std::uint32_t seed, const TraceSceneSpec& spec, int n_rays, int k) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int attempt = 0; attempt < 200; ++attempt) {
    Case c;
    c.k = k;
    c.scene = random_trace_scene<double>(rng, spec);
    c.rays = random_rays<double>(rng, n_rays, 2.5, 0.4);
    c.rays.t_min = 0.05;
    const std::size_t n = c.rays.count();
    for (auto* v : {&c.w.color, &c.w.depth, &c.w.alpha, &c.w.extras}) v->clear();
    for (std::size_t i = 0; i < 3 * n; ++i) c.w.color.push_back(u(rng));
    for (std::size_t i = 0; i < n; ++i) c.w.depth.push_back(u(rng));
    for (std::size_t i = 0; i < n; ++i) c.w.alpha.push_back(u(rng));
    for (std::size_t i = 0; i < n * std::size_t(spec.n_extras); ++i) c.w.extras.push_back(u(rng));
    if (far_from_thresholds(c)) return c;
  }
  ADD_FAILURE() << "no threshold-free scene found for seed " << seed;
  return {};
}

// Central differences of the loss for every entry of one parameter array, against the analytic gradient.
void check_group(Case c, const std::string& name, std::function<std::vector<double>&(Case&)> param,
                 const std::vector<double>& grad, std::size_t stride = 1, std::size_t used = 1) {
  const double h = 1e-6;
  std::vector<double>& p = param(c);
  ASSERT_EQ(p.size(), grad.size()) << name;
  int checked = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (i % stride >= used) continue;  // e.g. SH coefficients above the degree
    const double keep = p[i];
    p[i] = keep + h;
    const double lp = loss(c);
    p[i] = keep - h;
    const double lm = loss(c);
    p[i] = keep;
    const double fd = (lp - lm) / (2 * h);
    EXPECT_NEAR(grad[i], fd, 2e-7 + 2e-5 * std::max(std::abs(fd), std::abs(grad[i]))) << name << "[" << i << "]";
    ++checked;
  }
  EXPECT_GT(checked, 0) << name;
}

void check_all(const Case& c) {
  const Grads g = analytic(c);
  double nonzero = 0;
  for (double v : g.positions) nonzero += std::abs(v);
  EXPECT_GT(nonzero, 0.0) << "the scene produced no gradient at all";
  check_group(c, "positions", [](Case& x) -> std::vector<double>& { return x.scene.positions; }, g.positions);
  check_group(c, "log_scales", [](Case& x) -> std::vector<double>& { return x.scene.log_scales; }, g.log_scales);
  check_group(c, "rotations", [](Case& x) -> std::vector<double>& { return x.scene.rotations; }, g.rotations);
  check_group(c, "opacity_logits", [](Case& x) -> std::vector<double>& { return x.scene.logits; }, g.logits);
  check_group(c, "sh", [](Case& x) -> std::vector<double>& { return x.scene.sh; }, g.sh, 48,
              std::size_t(3 * gmath::sh_coeff_count(c.scene.sh_degree)));
  if (c.scene.n_extras)
    check_group(c, "extras", [](Case& x) -> std::vector<double>& { return x.scene.extras; }, g.extras);
  if (!c.scene.emit.empty())
    check_group(c, "emit", [](Case& x) -> std::vector<double>& { return x.scene.emit; }, g.emit);
  check_group(c, "ray origins", [](Case& x) -> std::vector<double>& { return x.rays.origins; }, g.origins);
  check_group(c, "ray directions", [](Case& x) -> std::vector<double>& { return x.rays.directions; }, g.directions);
}

}  // namespace

TEST(TraceGradients, PlainSceneEveryParameterAndRay) {
  TraceSceneSpec spec;
  for (std::uint32_t seed : {1u, 2u}) check_all(make_case(seed, spec, 6, 64));
}

TEST(TraceGradients, EmitWeightsAnd3dFilter) {
  TraceSceneSpec spec;
  spec.emit = true;
  spec.filter3d = true;
  check_all(make_case(3, spec, 6, 64));
}

TEST(TraceGradients, OpaqueRaysInSeveralRounds) {
  // High opacities stop rays early; two hits per round exercises the round tail sums of the backward pass.
  TraceSceneSpec spec;
  spec.count = 8;
  spec.logit_lo = 2.0;
  spec.logit_hi = 4.0;
  spec.spread = 0.35;
  for (int k : {1, 2, 64}) check_all(make_case(4, spec, 6, k));
}

TEST(TraceGradients, LowDegreeNoExtrasAnisotropic) {
  TraceSceneSpec spec;
  spec.sh_degree = 1;
  spec.n_extras = 0;
  spec.anisotropy = 0.8;
  check_all(make_case(5, spec, 6, 3));
}
