// The production (float) backward pass of GaussianTracer against the double-precision backward of the same
// maths (checked by finite differences in test_trace_gradients.cpp), on Embree and the LBVH; round sizes,
// the gradient-scratch cap and the accumulate/write contract; the CUDA backend's ordered backward
// (trace_backward_ordered.h) run on the CPU: the same gradients, bit for bit the same in every chunking.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "render/trace/gaussian_tracer.h"
#include "render/trace/trace_backward_ordered.h"
#include "render/trace/trace_cpu.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_trace_scenes.h"

using namespace goris;
using namespace goris::test;
namespace tr = goris::trace;

namespace {

template <class T>
struct AllGrads {
  std::vector<T> positions, log_scales, rotations, logits, sh, extras, emit, origins, directions;
  AllGrads(std::size_t N, std::size_t E, std::size_t n)
      : positions(3 * N), log_scales(3 * N), rotations(4 * N), logits(N), sh(48 * N), extras(E * N), emit(N),
        origins(3 * n), directions(3 * n) {}
  std::vector<std::pair<const char*, const std::vector<T>*>> groups() const {
    return {{"positions", &positions}, {"log_scales", &log_scales}, {"rotations", &rotations},
            {"opacity_logits", &logits}, {"sh", &sh}, {"extras", &extras}, {"emit", &emit},
            {"ray origins", &origins}, {"ray directions", &directions}};
  }
};

struct Upstream {
  std::vector<float> color, depth, alpha, extras;
};

struct Problem {
  SceneArrays<float> scene;
  TraceRaySet<float> rays;
  Upstream up;
};

// A scene, rays and random dL/d(outputs); rays whose float and double hit counts differ (a Gaussian at a
// threshold) get no gradient, so both precisions differentiate the same function.
Problem make_problem(std::uint32_t seed) {
  std::mt19937 rng(seed);
  TraceSceneSpec spec;
  spec.count = 200;
  spec.spread = 1.0;
  spec.log_scale_lo = std::log(0.03);
  spec.log_scale_hi = std::log(0.15);
  spec.anisotropy = 0.7;
  spec.logit_lo = -2.0;
  spec.logit_hi = 3.0;
  spec.emit = true;
  spec.filter3d = true;
  Problem p;
  p.scene = random_trace_scene<float>(rng, spec);
  p.rays = random_rays<float>(rng, 300, 2.0, 0.6);
  const auto rf = reference_trace(p.scene, p.rays);
  TraceRaySet<double> rays_d;
  rays_d.origins.assign(p.rays.origins.begin(), p.rays.origins.end());
  rays_d.directions.assign(p.rays.directions.begin(), p.rays.directions.end());
  const auto rd = reference_trace(p.scene.cast<double>(), rays_d);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  const std::size_t n = p.rays.count(), E = std::size_t(p.scene.n_extras);
  for (std::size_t r = 0; r < n; ++r) {
    const float on = rf[r].hits == rd[r].hits ? 1.f : 0.f;
    for (int k = 0; k < 3; ++k) p.up.color.push_back(on * u(rng));
    p.up.depth.push_back(on * u(rng));
    p.up.alpha.push_back(on * u(rng));
    for (std::size_t e = 0; e < E; ++e) p.up.extras.push_back(on * u(rng));
  }
  return p;
}

AllGrads<float> tracer_grads(const Problem& p, const TraceSettings& settings) {
  GaussianTracer tracer(Device::CPU, settings);
  tracer.build(float_view(p.scene), p.scene.emit.data());
  AllGrads<float> g(std::size_t(p.scene.count), std::size_t(p.scene.n_extras), p.rays.count());
  GaussianGradView gv;
  gv.positions = g.positions.data();
  gv.log_scales = g.log_scales.data();
  gv.rotations = g.rotations.data();
  gv.opacity_logits = g.logits.data();
  gv.sh = g.sh.data();
  gv.extras = g.extras.data();
  tracer.backward(p.rays.view(), TraceOutputGrads{p.up.color.data(), p.up.depth.data(), p.up.alpha.data(), p.up.extras.data()},
                  gv, TraceRayGrads{g.origins.data(), g.directions.data()}, g.emit.data());
  return g;
}

// The CPU backward (per-thread records) or the CUDA backend's ordered backward run on the CPU with
// `budget` bytes of records, in precision T, against brute-force hits.
enum class Backward { PerThread, Ordered };

template <class T>
AllGrads<T> reference_grads(const Problem& p, Backward how = Backward::PerThread,
                            std::size_t budget = std::size_t(1) << 30) {
  const SceneArrays<T> s = p.scene.cast<T>();
  TraceRaySet<T> rays;
  rays.origins.assign(p.rays.origins.begin(), p.rays.origins.end());
  rays.directions.assign(p.rays.directions.begin(), p.rays.directions.end());
  const auto gv = s.view();
  const auto prims = tr::make_prims_cpu(gv);
  tr::TraceScene<T> sc{s.count, prims.data(), s.sh.data(), s.sh_degree, s.extras.data(), s.n_extras, s.emit.data()};
  AllGrads<T> g(std::size_t(s.count), std::size_t(s.n_extras), rays.count());
  GaussianGradsT<T> gg;
  gg.positions = g.positions.data();
  gg.log_scales = g.log_scales.data();
  gg.rotations = g.rotations.data();
  gg.opacity_logits = g.logits.data();
  gg.sh = g.sh.data();
  gg.extras = g.extras.data();
  const std::vector<T> c(p.up.color.begin(), p.up.color.end()), d(p.up.depth.begin(), p.up.depth.end()),
      a(p.up.alpha.begin(), p.up.alpha.end()), e(p.up.extras.begin(), p.up.extras.end());
  const TraceOutputGradsT<T> up{c.data(), d.data(), a.data(), e.data()};
  const TraceRayGradsT<T> rg{g.origins.data(), g.directions.data()};
  const tr::BruteForceCollector<T> collector{prims.data(), sc.count};
  if (how == Backward::Ordered)
    tr::backward_ordered<4>(Device::CPU, sc, collector, gv, rays.view(), up, gg, rg, g.emit.data(), budget);
  else
    tr::backward_cpu(sc, gv, rays.view(), 64, up, gg, rg, g.emit.data(), budget, [&] { return collector; });
  return g;
}

AllGrads<double> double_grads(const Problem& p) { return reference_grads<double>(p); }

// Every entry within rel_tol of the group's largest magnitude (gradients of hits near thresholds are noisy
// in float, relative to the group, not to themselves).
template <class A, class B>
void expect_close(const AllGrads<A>& x, const AllGrads<B>& y, double rel_tol, const char* what) {
  const auto gx = x.groups();
  const auto gy = y.groups();
  for (std::size_t k = 0; k < gx.size(); ++k) {
    const auto& vx = *gx[k].second;
    const auto& vy = *gy[k].second;
    double scale = 0;
    for (auto v : vy) scale = std::max(scale, std::abs(double(v)));
    EXPECT_GT(scale, 0.0) << what << " " << gx[k].first << " has no gradient at all";
    int bad = 0;
    for (std::size_t i = 0; i < vx.size() && bad < 3; ++i)
      if (std::abs(double(vx[i]) - double(vy[i])) > rel_tol * scale) {
        ++bad;
        ADD_FAILURE() << what << " " << gx[k].first << "[" << i << "]: " << vx[i] << " vs " << vy[i]
                      << " (group max " << scale << ")";
      }
  }
}

}  // namespace

TEST(TraceBackward, FloatTracersAgreeWithTheDoubleReference) {
  const Problem p = make_problem(21);
  const auto ref = double_grads(p);
  for (TraceAccel a : {TraceAccel::Embree, TraceAccel::Lbvh}) {
    TraceSettings s;
    s.cpu_accel = a;
    expect_close(tracer_grads(p, s), ref, 2e-5, a == TraceAccel::Embree ? "embree" : "lbvh");
  }
}

TEST(TraceBackward, RoundSizeAndScratchCapDoNotChangeGradients) {
  const Problem p = make_problem(22);
  TraceSettings base;
  const auto ref = tracer_grads(p, base);
  for (int k : {1, 4}) {
    TraceSettings s;
    s.hits_per_round = k;
    expect_close(tracer_grads(p, s), ref, 5e-5, "small rounds");
  }
  TraceSettings one_thread;
  one_thread.max_grad_scratch_bytes = 1;  // one accumulator: a single worker
  // The same terms summed in another grouping (one slot instead of one per thread): float rounding only.
  expect_close(tracer_grads(p, one_thread), ref, 5e-6, "scratch cap");
}

TEST(TraceBackward, ParameterGradientsAccumulateRayGradientsAreWritten) {
  const Problem p = make_problem(23);
  GaussianTracer tracer;
  tracer.build(float_view(p.scene), p.scene.emit.data());
  const std::size_t N = std::size_t(p.scene.count), n = p.rays.count();
  std::vector<float> dpos(3 * N), dorig(3 * n, 123.f);
  GaussianGradView gv;
  gv.positions = dpos.data();
  const TraceOutputGrads up{p.up.color.data(), p.up.depth.data(), p.up.alpha.data(), p.up.extras.data()};
  tracer.backward(p.rays.view(), up, gv, TraceRayGrads{dorig.data(), nullptr});
  const auto once = dpos;
  const auto orig_once = dorig;
  tracer.backward(p.rays.view(), up, gv, TraceRayGrads{dorig.data(), nullptr});
  for (std::size_t i = 0; i < dpos.size(); ++i) EXPECT_NEAR(dpos[i], 2 * once[i], 1e-6 * (1 + std::abs(once[i])));
  EXPECT_EQ(dorig, orig_once);
  bool any = false;
  for (float v : orig_once) any = any || (v != 0.f && v != 123.f);
  EXPECT_TRUE(any);
}

// The CUDA backend's backward (records summed per Gaussian in ray order) is the same maths: it agrees with
// the CPU's in double precision, and in float its sums are the same bits however the rays are chunked
// (one chunk; chunks of a few rays, some traced twice after overflowing their slots) and from run to run.
TEST(TraceBackward, OrderedBackwardAgreesAndRepeatsBitForBitInEveryChunking) {
  const Problem p = make_problem(24);
  const auto ref = double_grads(p);
  expect_close(reference_grads<double>(p, Backward::Ordered), ref, 1e-12, "ordered (double)");
  const auto one_chunk = reference_grads<float>(p, Backward::Ordered);
  expect_close(one_chunk, ref, 2e-5, "ordered (float)");
  const std::size_t stride = std::size_t(tr::record_stride(p.scene.sh_degree, p.scene.n_extras));
  const std::size_t record = stride * sizeof(float) + 24;  // the budget per record backward_ordered assumes
  for (std::size_t records : {1, 7, 100, 1000}) {
    const auto chunked = reference_grads<float>(p, Backward::Ordered, records * record);
    const auto a = chunked.groups(), b = one_chunk.groups();
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_EQ(*a[k].second, *b[k].second) << a[k].first << " with a budget of " << records << " records";
  }
  const auto again = reference_grads<float>(p, Backward::Ordered);
  EXPECT_EQ(again.positions, one_chunk.positions);
  EXPECT_EQ(again.sh, one_chunk.sh);
}
