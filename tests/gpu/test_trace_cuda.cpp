// The CUDA tracer (LBVH built on the GPU) against the CPU tracer (Embree) on the same inputs: forward
// outputs and hit counts, and the backward pass, on random scenes (tiny, cluttered, after motion) and on the
// tracer_garden fixture. Skips without a GPU.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/compute/buffer.h"
#include "render/trace/gaussian_tracer.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_trace_scenes.h"

using namespace goris;
using namespace goris::test;

namespace {

struct Result {
  std::vector<float> color, depth, alpha, extras, dpos, dscale, drot, dlogit, dsh, dextras, dorig, ddir;
  std::vector<std::int32_t> hits;
};

// Uploads scene and rays to `d`, traces forward and backward with fixed upstream gradients, downloads all.
Result run_on(Device d, const SceneArrays<float>& s, const TraceRaySet<float>& rays) {
  const std::size_t N = std::size_t(s.count), n = rays.count(), E = std::size_t(s.n_extras);
  auto up = [d](const std::vector<float>& v) { return Buffer<float>(v.empty() ? std::vector<float>(1) : v, d); };
  Buffer<float> pos = up(s.positions), ls = up(s.log_scales), rot = up(s.rotations), lg = up(s.logits), sh = up(s.sh),
                ex = up(s.extras);
  GaussianView v;
  v.count = s.count;
  v.positions = pos.data();
  v.log_scales = ls.data();
  v.rotations = rot.data();
  v.opacity_logits = lg.data();
  v.sh = sh.data();
  v.sh_degree = s.sh_degree;
  v.extras = E ? ex.data() : nullptr;
  v.n_extras = s.n_extras;
  GaussianTracer tracer(d);
  tracer.build(v);
  Buffer<float> o = up(rays.origins), dir = up(rays.directions);
  Buffer<float> color(3 * n, d), depth(n, d), alpha(n, d), extras(std::max<std::size_t>(1, E * n), d);
  Buffer<std::int32_t> hits(n, d);
  const TraceRays tr{o.data(), dir.data(), n, rays.t_min};
  tracer.trace(tr, TraceOutputs{color.data(), depth.data(), alpha.data(), extras.data(), hits.data()});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<float> gc(3 * n), gd(n), ga(n), ge(std::max<std::size_t>(1, E * n));
  for (auto* vec : {&gc, &gd, &ga, &ge})
    for (auto& x : *vec) x = u(rng);
  Buffer<float> bgc = up(gc), bgd = up(gd), bga = up(ga), bge = up(ge);
  Buffer<float> dpos(3 * N + 1, d), dls(3 * N + 1, d), drot(4 * N + 1, d), dlg(N + 1, d), dsh(48 * N + 1, d),
      dex(E * N + 1, d), dorig(3 * n, d), ddir(3 * n, d);
  for (auto* b : {&dpos, &dls, &drot, &dlg, &dsh, &dex}) b->fill_zero();
  GaussianGradView gv;
  gv.positions = dpos.data();
  gv.log_scales = dls.data();
  gv.rotations = drot.data();
  gv.opacity_logits = dlg.data();
  gv.sh = dsh.data();
  gv.extras = dex.data();
  tracer.backward(tr, TraceOutputGrads{bgc.data(), bgd.data(), bga.data(), E ? bge.data() : nullptr}, gv,
                  TraceRayGrads{dorig.data(), ddir.data()});
  Result r;
  r.color = color.to_host();
  r.depth = depth.to_host();
  r.alpha = alpha.to_host();
  r.extras = extras.to_host();
  r.hits = hits.to_host();
  r.dpos = dpos.to_host();
  r.dscale = dls.to_host();
  r.drot = drot.to_host();
  r.dlogit = dlg.to_host();
  r.dsh = dsh.to_host();
  r.dextras = dex.to_host();
  r.dorig = dorig.to_host();
  r.ddir = ddir.to_host();
  return r;
}

// Within rel of the group's largest magnitude (float sums in a different order).
void expect_group_close(const std::vector<float>& a, const std::vector<float>& b, double rel, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  double scale = 1e-12;
  for (float x : b) scale = std::max(scale, double(std::abs(x)));
  int bad = 0;
  for (std::size_t i = 0; i < a.size() && bad < 3; ++i)
    if (std::abs(double(a[i]) - double(b[i])) > rel * scale) {
      ++bad;
      ADD_FAILURE() << what << "[" << i << "]: cuda " << a[i] << " vs cpu " << b[i] << " (group max " << scale << ")";
    }
}

void compare(const SceneArrays<float>& s, const TraceRaySet<float>& rays) {
  const Result g = run_on(Device::CUDA, s, rays), c = run_on(Device::CPU, s, rays);
  int hit_diff = 0;
  for (std::size_t r = 0; r < rays.count(); ++r) hit_diff += g.hits[r] != c.hits[r];
  EXPECT_EQ(hit_diff, 0) << "rays whose hit counts differ between CUDA and CPU";
  expect_group_close(g.color, c.color, 1e-4, "color");
  expect_group_close(g.depth, c.depth, 1e-4, "depth");
  expect_group_close(g.alpha, c.alpha, 1e-4, "alpha");
  expect_group_close(g.extras, c.extras, 1e-4, "extras");
  expect_group_close(g.dpos, c.dpos, 1e-4, "d positions");
  expect_group_close(g.dscale, c.dscale, 1e-4, "d log_scales");
  expect_group_close(g.drot, c.drot, 1e-4, "d rotations");
  expect_group_close(g.dlogit, c.dlogit, 1e-4, "d opacity_logits");
  expect_group_close(g.dsh, c.dsh, 1e-4, "d sh");
  expect_group_close(g.dextras, c.dextras, 1e-4, "d extras");
  expect_group_close(g.dorig, c.dorig, 1e-4, "d ray origins");
  expect_group_close(g.ddir, c.ddir, 1e-4, "d ray directions");
}

}  // namespace

TEST(TraceCuda, RandomScenesMatchCpu) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(31);
  for (int n : {1, 2, 7, 500, 5000}) {
    TraceSceneSpec spec;
    spec.count = n;
    spec.spread = 1.0;
    spec.log_scale_lo = std::log(0.02);
    spec.log_scale_hi = std::log(n < 10 ? 0.4 : 0.12);
    spec.anisotropy = 1.0;
    spec.logit_lo = -3.0;
    spec.logit_hi = 3.0;
    const auto scene = random_trace_scene<float>(rng, spec);
    const auto rays = random_rays<float>(rng, 2000, 2.0, 0.7);
    SCOPED_TRACE(n);
    compare(scene, rays);
  }
}

TEST(TraceCuda, FixtureMatchesCpu) {
  GORIS_REQUIRE_GPU();
  GORIS_REQUIRE_SHARED("fixtures/tracer_garden");
  const FixtureScene f = load_tracer_fixture(shared_dir());
  compare(f.scene, f.rays);
}

// The backward pass sums each Gaussian's per-ray records in ray order (trace_backward_ordered.h), so the
// same inputs give the same gradients bit for bit, run after run (the first CUDA version's atomics did not).
TEST(TraceCuda, BackwardRepeatsBitForBit) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(32);
  TraceSceneSpec spec;
  spec.count = 3000;
  spec.spread = 1.0;
  spec.log_scale_lo = std::log(0.03);
  spec.log_scale_hi = std::log(0.2);
  spec.logit_lo = -1.0;
  spec.logit_hi = 3.0;
  const auto scene = random_trace_scene<float>(rng, spec);
  const auto rays = random_rays<float>(rng, 20000, 2.0, 0.7);
  const Result a = run_on(Device::CUDA, scene, rays), b = run_on(Device::CUDA, scene, rays);
  EXPECT_EQ(a.dpos, b.dpos);
  EXPECT_EQ(a.dscale, b.dscale);
  EXPECT_EQ(a.drot, b.drot);
  EXPECT_EQ(a.dlogit, b.dlogit);
  EXPECT_EQ(a.dsh, b.dsh);
  EXPECT_EQ(a.dorig, b.dorig);
}
