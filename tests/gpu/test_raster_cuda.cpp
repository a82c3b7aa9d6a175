// The CUDA rasterizer against the CPU one on the same inputs: per-Gaussian projection, every G-buffer
// channel (relative L2 error < 1e-4) and every parameter gradient (relative L2 error < 1e-3). Skips without
// a CUDA device.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "render/raster/blend.h"
#include "render/raster/rasterizer.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_raster_scenes.h"

using namespace goris;

namespace {

double rel_l2(const std::vector<float>& a, const std::vector<float>& b) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += double(a[i] - b[i]) * double(a[i] - b[i]);
    den += double(b[i]) * double(b[i]);
  }
  return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

struct DeviceScene {
  std::vector<Buffer<float>> bufs;
  GaussianView view;
};

DeviceScene upload(const test::RasterScene<float>& s, Device d) {
  DeviceScene ds;
  for (const auto* v : {&s.positions, &s.log_scales, &s.rotations, &s.opacity_logits, &s.sh, &s.extras, &s.filter3d})
    ds.bufs.emplace_back(*v, d);
  ds.view.count = s.count;
  ds.view.positions = ds.bufs[0].data();
  ds.view.log_scales = ds.bufs[1].data();
  ds.view.rotations = ds.bufs[2].data();
  ds.view.opacity_logits = ds.bufs[3].data();
  ds.view.sh = ds.bufs[4].data();
  ds.view.sh_degree = s.sh_degree;
  ds.view.extras = ds.bufs[5].data();
  ds.view.n_extras = s.n_extras;
  ds.view.filter3d_var = s.use_filter3d ? ds.bufs[6].data() : nullptr;
  return ds;
}

struct RunResult {
  std::vector<float> color, alpha, depth, median, normal, extras;
  std::vector<float> means2d, conics, colors, depths, planes, normals;
  std::vector<std::int32_t> radii;
  std::vector<float> d_pos, d_ls, d_rot, d_op, d_sh, d_ext, d_m2;
};

RunResult run(const test::RasterScene<float>& s, const Camera& cam, const RasterSettings& rs, Device d,
              const std::vector<std::vector<float>>& dl) {
  DeviceScene ds = upload(s, d);
  const RasterOutput out = rasterize(ds.view, cam, rs, d);
  RunResult r;
  const GBuffer& gb = out.gbuffer;
  r.color = gb.color.to_host(), r.alpha = gb.alpha.to_host(), r.depth = gb.depth.to_host();
  r.median = gb.median_depth.to_host(), r.normal = gb.normal.to_host(), r.extras = gb.extras.to_host();
  const RasterState& st = out.state;
  r.means2d = st.means2d.to_host(), r.conics = st.conics.to_host(), r.colors = st.colors.to_host();
  r.depths = st.depths.to_host(), r.planes = st.depth_planes.to_host(), r.normals = st.normals.to_host();
  r.radii = st.radii.to_host();
  std::vector<Buffer<float>> g;
  for (const auto& v : dl) g.emplace_back(v, d);
  const GBufferGrad go{g[0].data(), g[1].data(), g[2].data(), g[3].data(), g[4].data(), g[5].data()};
  const std::size_t n = std::size_t(s.count);
  std::vector<Buffer<float>> grads;
  for (std::size_t k : {3 * n, 3 * n, 4 * n, n, 48 * n, n * std::size_t(s.n_extras), n}) {
    grads.emplace_back(std::max<std::size_t>(k, 1), d);
    grads.back().fill_zero();
  }
  const GaussianGradView gv{grads[0].data(), grads[1].data(), grads[2].data(), grads[3].data(),
                            grads[4].data(), grads[5].data(), grads[6].data()};
  rasterize_backward(ds.view, st, go, gv);
  r.d_pos = grads[0].to_host(), r.d_ls = grads[1].to_host(), r.d_rot = grads[2].to_host();
  r.d_op = grads[3].to_host(), r.d_sh = grads[4].to_host(), r.d_ext = grads[5].to_host(), r.d_m2 = grads[6].to_host();
  return r;
}

// Random dL/d(colour, alpha, depth, median depth, normal, extras).
std::vector<std::vector<float>> random_upstream(const test::RasterScene<float>& s, const Camera& cam) {
  const std::size_t P = std::size_t(cam.width) * cam.height;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<std::vector<float>> dl;
  for (std::size_t n : {3 * P, P, P, P, 3 * P, std::size_t(s.n_extras) * P}) {
    dl.emplace_back(std::max<std::size_t>(n, 1));
    for (auto& x : dl.back()) x = u(rng);
  }
  return dl;
}

void compare(const test::RasterScene<float>& s, const Camera& cam, const RasterSettings& rs) {
  const auto dl = random_upstream(s, cam);
  const RunResult c = run(s, cam, rs, Device::CPU, dl);
  const RunResult g = run(s, cam, rs, Device::CUDA, dl);
  EXPECT_EQ(c.radii, g.radii);
  EXPECT_LT(rel_l2(g.means2d, c.means2d), 1e-5);
  EXPECT_LT(rel_l2(g.conics, c.conics), 1e-4);
  EXPECT_LT(rel_l2(g.colors, c.colors), 1e-4);
  EXPECT_LT(rel_l2(g.depths, c.depths), 1e-5);
  EXPECT_LT(rel_l2(g.planes, c.planes), 1e-4);
  EXPECT_LT(rel_l2(g.normals, c.normals), 1e-4);
  EXPECT_LT(rel_l2(g.color, c.color), 1e-4) << "color";
  EXPECT_LT(rel_l2(g.alpha, c.alpha), 1e-4) << "alpha";
  EXPECT_LT(rel_l2(g.depth, c.depth), 1e-4) << "depth";
  EXPECT_LT(rel_l2(g.median, c.median), 1e-4) << "median depth";
  EXPECT_LT(rel_l2(g.normal, c.normal), 1e-4) << "normal";
  if (s.n_extras > 0) {
    EXPECT_LT(rel_l2(g.extras, c.extras), 1e-4) << "extras";
  }
  EXPECT_LT(rel_l2(g.d_pos, c.d_pos), 1e-3) << "d positions";
  EXPECT_LT(rel_l2(g.d_ls, c.d_ls), 1e-3) << "d log_scales";
  EXPECT_LT(rel_l2(g.d_rot, c.d_rot), 1e-3) << "d rotations";
  EXPECT_LT(rel_l2(g.d_op, c.d_op), 1e-3) << "d opacity_logits";
  EXPECT_LT(rel_l2(g.d_sh, c.d_sh), 1e-3) << "d sh";
  if (s.n_extras > 0) {
    EXPECT_LT(rel_l2(g.d_ext, c.d_ext), 1e-3) << "d extras";
  }
  EXPECT_LT(rel_l2(g.d_m2, c.d_m2), 1e-3) << "mean2d gradient norm";
}

}  // namespace

TEST(RasterCuda, MatchesCpuOnRandomScene) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(42);
  test::SceneSpec spec;
  spec.count = 3000;
  spec.n_extras = 5;
  spec.spread = 1.2f;
  spec.scale_lo = 0.01f;
  spec.scale_hi = 0.08f;
  spec.filter3d = true;
  const auto scene = test::random_scene<float>(rng, spec);
  const Camera cam = test::random_camera(rng, 150, 110, 140.f, 4.f);
  RasterSettings rs = RasterSettings::mip_splatting();
  rs.background = glm::vec3(0.2f, 0.4f, 0.6f);
  compare(scene, cam, rs);
}

TEST(RasterCuda, MatchesCpuClassicRuleAndShDegrees) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(7);
  for (int degree = 0; degree <= 3; ++degree) {
    SCOPED_TRACE("SH degree " + std::to_string(degree));
    test::SceneSpec spec;
    spec.count = 800;
    spec.sh_degree = degree;
    spec.n_extras = degree;  // 0 extras included
    spec.scale_lo = 0.02f;
    spec.scale_hi = 0.15f;
    const auto scene = test::random_scene<float>(rng, spec);
    compare(scene, test::random_camera(rng, 64, 48, 60.f, 4.f), RasterSettings::classic_3dgs());
  }
}

// The blend's backward adds each tile's warp sums in warp order (no atomics): the gradients repeat bit for
// bit, here with the most extra channels (the widest gradient slots).
TEST(RasterCuda, BackwardRepeatsBitForBit) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(11);
  test::SceneSpec spec;
  spec.count = 4000;
  spec.n_extras = raster::kMaxExtras;
  spec.scale_lo = 0.01f;
  spec.scale_hi = 0.1f;
  const auto scene = test::random_scene<float>(rng, spec);
  const Camera cam = test::random_camera(rng, 200, 150, 180.f, 4.f);
  const auto dl = random_upstream(scene, cam);
  const RasterSettings rs = RasterSettings::mip_splatting();
  const RunResult a = run(scene, cam, rs, Device::CUDA, dl), b = run(scene, cam, rs, Device::CUDA, dl);
  EXPECT_EQ(a.d_pos, b.d_pos);
  EXPECT_EQ(a.d_ls, b.d_ls);
  EXPECT_EQ(a.d_rot, b.d_rot);
  EXPECT_EQ(a.d_op, b.d_op);
  EXPECT_EQ(a.d_sh, b.d_sh);
  EXPECT_EQ(a.d_ext, b.d_ext);
  const RunResult c = run(scene, cam, rs, Device::CPU, dl);
  EXPECT_LT(rel_l2(a.d_ext, c.d_ext), 1e-3) << "d extras against the CPU";
  EXPECT_LT(rel_l2(a.d_pos, c.d_pos), 1e-3) << "d positions against the CPU";
}
