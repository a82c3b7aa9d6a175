// The accelerated CPU tracers (Embree, and the LBVH the CUDA backend uses, run on the CPU) against an
// independent brute-force reference on random scenes: Gaussians behind the ray origin, grazing rays at the
// 1/255 level, very flat and very elongated Gaussians, refits after motion, every round size; plus the
// emit weights, the float backward against the double one, and bad input.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/util/error.h"
#include "render/trace/gaussian_tracer.h"
#include "render/trace/trace_cpu.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_trace_scenes.h"

using namespace goris;
using namespace goris::test;

namespace {

struct Outputs {
  std::vector<float> color, depth, alpha, extras;
  std::vector<std::int32_t> hits;
};

Outputs run(GaussianTracer& tracer, const TraceRaySet<float>& rays, int n_extras) {
  const std::size_t n = rays.count();
  Outputs o{std::vector<float>(3 * n, -1.f), std::vector<float>(n, -1.f), std::vector<float>(n, -1.f),
            std::vector<float>(n * std::size_t(n_extras), -1.f), std::vector<std::int32_t>(n, -1)};
  tracer.trace(rays.view(), TraceOutputs{o.color.data(), o.depth.data(), o.alpha.data(), o.extras.data(), o.hits.data()});
  return o;
}

// Same hits as the reference on every ray and the same blended values up to float summation order.
void expect_matches_reference(const SceneArrays<float>& s, const TraceRaySet<float>& rays, const Outputs& o,
                              const char* what) {
  const auto ref = reference_trace(s, rays);
  int bad = 0;
  for (std::size_t r = 0; r < rays.count() && bad < 5; ++r) {
    const auto& e = ref[r];
    auto near = [](double a, double b) { return std::abs(a - b) <= 2e-5 * (1 + std::abs(b)); };
    bool ok = o.hits[r] == e.hits && near(o.alpha[r], e.alpha) && near(o.depth[r], e.depth);
    for (int k = 0; k < 3; ++k) ok = ok && near(o.color[3 * r + k], e.color[k]);
    for (int x = 0; x < s.n_extras; ++x) ok = ok && near(o.extras[r * s.n_extras + x], e.extras[x]);
    if (!ok) {
      ++bad;
      ADD_FAILURE() << what << ": ray " << r << " hits " << o.hits[r] << " vs " << e.hits << ", alpha " << o.alpha[r]
                    << " vs " << e.alpha << ", depth " << o.depth[r] << " vs " << e.depth;
    }
  }
}

const TraceAccel kAccels[] = {TraceAccel::Embree, TraceAccel::Lbvh};
const char* accel_name(TraceAccel a) { return a == TraceAccel::Embree ? "embree" : "lbvh"; }

TraceSettings settings_for(TraceAccel a, int k = 64) {
  TraceSettings s;
  s.cpu_accel = a;
  s.hits_per_round = k;
  return s;
}

SceneArrays<float> cluttered_scene(std::mt19937& rng, int n, double anisotropy) {
  TraceSceneSpec spec;
  spec.count = n;
  spec.spread = 1.0;
  spec.log_scale_lo = std::log(0.02);
  spec.log_scale_hi = std::log(0.15);
  spec.anisotropy = anisotropy;
  spec.logit_lo = -4.0;  // some Gaussians never reach 1/255
  spec.logit_hi = 3.0;
  spec.n_extras = 2;
  return random_trace_scene<float>(rng, spec);
}

}  // namespace

TEST(TraceAccel, RandomScenesMatchBruteForceIncludingGaussiansBehindTheOrigin) {
  std::mt19937 rng(11);
  for (double aniso : {0.0, 1.5}) {
    const auto scene = cluttered_scene(rng, 400, aniso);
    auto rays = random_rays<float>(rng, 400, 2.0, 0.8);  // origins from 0.6 to 2 from the centre: many inside
    for (TraceAccel a : kAccels) {
      GaussianTracer tracer(Device::CPU, settings_for(a));
      tracer.build(float_view(scene));
      expect_matches_reference(scene, rays, run(tracer, rays, scene.n_extras), accel_name(a));
    }
  }
}

TEST(TraceAccel, GrazingRaysAtTheCutoffLevel) {
  // Rays whose closest approach to a Gaussian lies on (or within 1e-4 of) its 1/255 ellipsoid: at random
  // points of it, and at the points where it touches its bounding box (direction perpendicular to the axis).
  std::mt19937 rng(12);
  auto scene = cluttered_scene(rng, 60, 1.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  TraceRaySet<float> rays;
  const auto prims = trace::make_prims_cpu(scene.cast<double>().view());
  for (int i = 0; i < scene.count; ++i) {
    const double L = std::log(255.0 * prims[i].opacity);
    if (L <= 0) continue;
    const double r = std::sqrt(2 * L);
    const auto M = trace::prim_matrix(prims[i]);
    const auto Minv = glm::inverse(M);  // R S
    const glm::dvec3 mu(prims[i].mean[0], prims[i].mean[1], prims[i].mean[2]);
    for (double f : {0.9999, 1.0, 1.0001}) {
      const glm::dvec3 dc = glm::normalize(glm::dvec3(n01(rng), n01(rng), n01(rng)));
      const glm::dvec3 pc = glm::normalize(glm::cross(dc, glm::dvec3(n01(rng), n01(rng), n01(rng)))) * r * f;
      rays.add(mu + Minv * (pc - 4.0 * dc), Minv * dc);
      for (int axis = 0; axis < 3; ++axis)
        for (double sign : {-1.0, 1.0}) {
          glm::dvec3 e(0.0);
          e[axis] = sign;
          const glm::dvec3 u = glm::normalize(glm::transpose(Minv) * e) * r * f;  // extreme along e
          glm::dvec3 d = glm::cross(e, glm::dvec3(n01(rng), n01(rng), n01(rng)));  // tangent there
          d = glm::normalize(d);
          rays.add(mu + Minv * u - 3.0 * d, d);
        }
    }
  }
  ASSERT_GT(rays.count(), 400u);
  for (TraceAccel a : kAccels) {
    GaussianTracer tracer(Device::CPU, settings_for(a));
    tracer.build(float_view(scene));
    const Outputs o = run(tracer, rays, scene.n_extras);
    expect_matches_reference(scene, rays, o, accel_name(a));
    int hit_rays = 0;
    for (auto h : o.hits) hit_rays += h > 0;
    EXPECT_GT(hit_rays, int(rays.count()) / 3);
  }
}

TEST(TraceAccel, VeryFlatAndVeryElongatedGaussians) {
  std::mt19937 rng(13);
  auto scene = cluttered_scene(rng, 200, 0.5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < scene.count; ++i) {
    const int axis = i % 3;
    const bool flat = i % 2 == 0;
    for (int k = 0; k < 3; ++k)
      scene.log_scales[3 * i + k] = flat ? (k == axis ? std::log(1e-4f) : std::log(0.1f + 0.1f * u(rng)))
                                         : (k == axis ? std::log(0.6f) : std::log(0.004f));
    scene.logits[i] = 1.0f + 2.0f * u(rng);
  }
  const auto rays = random_rays<float>(rng, 600, 2.0, 0.8);
  for (TraceAccel a : kAccels) {
    GaussianTracer tracer(Device::CPU, settings_for(a));
    tracer.build(float_view(scene));
    const Outputs o = run(tracer, rays, scene.n_extras);
    expect_matches_reference(scene, rays, o, accel_name(a));
    int hit_rays = 0;
    for (auto h : o.hits) hit_rays += h > 0;
    EXPECT_GT(hit_rays, 100) << "the thin Gaussians should still be hit";
  }
}

TEST(TraceAccel, EveryRoundSizeGivesIdenticalResults) {
  std::mt19937 rng(14);
  const auto scene = cluttered_scene(rng, 300, 1.0);
  const auto rays = random_rays<float>(rng, 300, 2.0, 0.5);
  for (TraceAccel a : kAccels) {
    GaussianTracer all(Device::CPU, settings_for(a, 1 << 16));
    all.build(float_view(scene));
    const Outputs ref = run(all, rays, scene.n_extras);
    for (int k : {1, 2, 5, 64}) {
      GaussianTracer t(Device::CPU, settings_for(a, k));
      t.build(float_view(scene));
      const Outputs o = run(t, rays, scene.n_extras);
      EXPECT_EQ(o.hits, ref.hits) << accel_name(a) << " k=" << k;
      EXPECT_EQ(o.color, ref.color) << accel_name(a) << " k=" << k;
      EXPECT_EQ(o.depth, ref.depth) << accel_name(a) << " k=" << k;
      EXPECT_EQ(o.extras, ref.extras) << accel_name(a) << " k=" << k;
    }
  }
}

TEST(TraceAccel, RefitAfterMotionAndRebuildAfterCountChange) {
  std::mt19937 rng(15);
  auto scene = cluttered_scene(rng, 300, 1.0);
  const auto rays = random_rays<float>(rng, 300, 2.0, 0.6);
  std::normal_distribution<float> n01(0.f, 1.f);
  for (TraceAccel a : kAccels) {
    auto s = scene;
    GaussianTracer tracer(Device::CPU, settings_for(a));
    tracer.build(float_view(s));
    EXPECT_FALSE(tracer.last_build_refitted());
    for (int step = 0; step < 2; ++step) {
      for (auto& p : s.positions) p += 0.1f * n01(rng);
      for (auto& q : s.rotations) q += 0.2f * n01(rng);
      for (auto& l : s.log_scales) l += 0.2f * n01(rng);
      tracer.build(float_view(s));
      EXPECT_EQ(tracer.last_build_refitted(), a == TraceAccel::Embree);
      expect_matches_reference(s, rays, run(tracer, rays, s.n_extras), accel_name(a));
    }
    auto fewer = random_trace_scene<float>(rng, TraceSceneSpec{});
    tracer.build(float_view(fewer));
    EXPECT_FALSE(tracer.last_build_refitted());
    expect_matches_reference(fewer, rays, run(tracer, rays, fewer.n_extras), accel_name(a));
  }
}

// Gaussians below the 1/255 level have empty boxes. When the set of empty boxes changes at the same count
// (an opacity rising again, the reflection rays' transparency following new emit weights) the next build
// rebuilds instead of refitting, and traces exactly as a fresh tracer does (what a resumed run starts
// with); moved Gaussians with the same set still refit. The results match the brute-force reference.
TEST(TraceAccel, GaussiansThatBecomeVisibleOrInvisibleAreTracedAfterTheNextBuild) {
  std::mt19937 rng(19);
  auto scene = cluttered_scene(rng, 300, 1.0);
  const auto rays = random_rays<float>(rng, 300, 2.0, 0.6);
  const std::vector<float> visible = scene.logits;
  for (TraceAccel a : kAccels) {
    auto s = scene;
    for (int i = 0; i < s.count; i += 2) s.logits[std::size_t(i)] = -30.0f;  // half of them invisible
    GaussianTracer tracer(Device::CPU, settings_for(a));
    tracer.build(float_view(s));
    expect_matches_reference(s, rays, run(tracer, rays, s.n_extras), accel_name(a));
    s.logits = visible;  // all visible again, same count
    tracer.build(float_view(s));
    EXPECT_FALSE(tracer.last_build_refitted()) << accel_name(a);
    const Outputs all = run(tracer, rays, s.n_extras);
    expect_matches_reference(s, rays, all, accel_name(a));
    GaussianTracer fresh(Device::CPU, settings_for(a));
    fresh.build(float_view(s));
    EXPECT_EQ(run(fresh, rays, s.n_extras).color, all.color) << accel_name(a);
    for (auto& p : s.positions) p += 0.01f;  // moved, the same ones visible: a refit is right
    tracer.build(float_view(s));
    EXPECT_EQ(tracer.last_build_refitted(), a == TraceAccel::Embree);
    expect_matches_reference(s, rays, run(tracer, rays, s.n_extras), accel_name(a));
  }
}

TEST(TraceAccel, EmitWeightsScaleColourButEveryGaussianOccludes) {
  std::mt19937 rng(16);
  auto scene = cluttered_scene(rng, 200, 0.5);
  const auto rays = random_rays<float>(rng, 200, 2.0, 0.5);
  GaussianTracer tracer;
  tracer.build(float_view(scene));
  const Outputs plain = run(tracer, rays, scene.n_extras);
  std::vector<float> zero(std::size_t(scene.count), 0.f);
  tracer.build(float_view(scene), zero.data());
  const Outputs dark = run(tracer, rays, scene.n_extras);
  EXPECT_EQ(dark.alpha, plain.alpha);
  EXPECT_EQ(dark.hits, plain.hits);
  for (float c : dark.color) EXPECT_EQ(c, 0.f);
  scene.emit.resize(std::size_t(scene.count));
  for (int i = 0; i < scene.count; ++i) scene.emit[i] = float(i % 3) * 0.5f;
  tracer.build(float_view(scene), scene.emit.data());
  expect_matches_reference(scene, rays, run(tracer, rays, scene.n_extras), "emit");
}

TEST(TraceAccel, EmptySceneAndNoRays) {
  SceneArrays<float> empty;
  GaussianTracer tracer;
  tracer.build(float_view(empty));
  std::mt19937 rng(17);
  const auto rays = random_rays<float>(rng, 10, 2.0, 0.5);
  const Outputs o = run(tracer, rays, 0);
  for (std::size_t r = 0; r < rays.count(); ++r) {
    EXPECT_EQ(o.hits[r], 0);
    EXPECT_EQ(o.alpha[r], 0.f);
    EXPECT_EQ(o.color[3 * r], 0.f);
  }
  tracer.trace(TraceRays{}, TraceOutputs{});  // zero rays: nothing to do
}

TEST(TraceAccel, BadInputIsAnError) {
  std::mt19937 rng(18);
  auto scene = cluttered_scene(rng, 20, 0.0);
  const auto rays = random_rays<float>(rng, 4, 2.0, 0.5);
  GaussianTracer tracer;
  std::vector<float> c(12), d(4), a(4);
  EXPECT_THROW(tracer.trace(rays.view(), TraceOutputs{c.data(), d.data(), a.data()}), Error);  // not built
  GaussianView v = float_view(scene);
  v.sh_degree = 4;
  EXPECT_THROW(tracer.build(v), Error);
  v = float_view(scene);
  v.rotations = nullptr;
  EXPECT_THROW(tracer.build(v), Error);
  auto bad = scene;
  bad.positions[7] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(tracer.build(float_view(bad)), Error);
  bad = scene;
  for (int k = 0; k < 4; ++k) bad.rotations[4 * 3 + k] = 0.f;
  EXPECT_THROW(tracer.build(float_view(bad)), Error);
  tracer.build(float_view(scene));
  auto zero_dir = rays;
  zero_dir.directions[3] = zero_dir.directions[4] = zero_dir.directions[5] = 0.f;
  EXPECT_THROW(tracer.trace(zero_dir.view(), TraceOutputs{c.data(), d.data(), a.data()}), Error);
  auto neg = rays;
  neg.t_min = -1.f;
  EXPECT_THROW(tracer.trace(neg.view(), TraceOutputs{c.data(), d.data(), a.data()}), Error);
  TraceSettings s;
  s.hits_per_round = 0;
  EXPECT_THROW(GaussianTracer(Device::CPU, s), Error);
  if (!cuda_compiled()) EXPECT_THROW(GaussianTracer(Device::CUDA), Error);
}
