// Rasterizer behaviour that the fixture and the gradient checks do not pin down: RaDe-GS depth planes and
// normals on a flat Gaussian, the median-depth rule, extras, background, float against double, and the
// errors for bad input.
#include <cmath>
#include <random>
#include <vector>

#include "core/util/error.h"
#include "render/raster/raster_cpu.h"
#include "render/raster/rasterizer.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_raster_scenes.h"

using namespace goris;
using test::RasterScene;

namespace {

Camera front_camera(int w = 64, int h = 48, float f = 60.f) {
  Camera c;
  c.width = w, c.height = h;
  c.fx = c.fy = f;
  c.cx = 0.5f * w, c.cy = 0.5f * h;
  return c;  // identity pose: world = camera space
}

// One Gaussian per entry of `pos`, isotropic scale s (or flat with the given thin axis), SH DC only.
RasterScene<double> scene_of(const std::vector<glm::dvec3>& pos, const std::vector<double>& logit, double s,
                             const std::vector<double>& quat = {1, 0, 0, 0}, double thin = -1) {
  RasterScene<double> sc;
  sc.count = int(pos.size());
  sc.sh_degree = 0;
  sc.n_extras = 1;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    sc.positions.insert(sc.positions.end(), {pos[i].x, pos[i].y, pos[i].z});
    sc.log_scales.insert(sc.log_scales.end(), {std::log(s), std::log(s), std::log(thin > 0 ? thin : s)});
    sc.rotations.insert(sc.rotations.end(), quat.begin(), quat.end());
    sc.opacity_logits.push_back(logit[i]);
    for (int k = 0; k < 48; ++k) sc.sh.push_back(k < 3 ? 0.3 : 0.0);
    sc.extras.push_back(1.0);
    sc.filter3d.push_back(0.0);
  }
  return sc;
}

struct Render {
  GBufferT<double> gb;
  RasterStateT<double> st;
};

Render render(const RasterScene<double>& sc, const Camera& cam, RasterSettings rs = RasterSettings::classic_3dgs()) {
  Render r;
  raster::forward_cpu(sc.view(), cam, rs, r.gb, r.st);
  return r;
}

}  // namespace

// A flat disk tilted by 35 degrees: its depth plane is the disk's plane to first order around the centre,
// and its normal is the disk normal, facing the camera.
TEST(RasterBasics, FlatGaussianDepthPlaneAndNormal) {
  const double a = 35.0 * M_PI / 180.0;
  const glm::dvec3 mu(0.15, -0.1, 3.0);
  const std::vector<double> q = {std::cos(a / 2), std::sin(a / 2), 0, 0};  // rotation about x
  const RasterScene<double> sc = scene_of({mu}, {0.0}, 0.3, q, 1e-4);
  const Camera cam = front_camera();
  const Render r = render(sc, cam);
  ASSERT_GT(r.st.radii[0], 0);
  // Disk normal = R e_z, oriented toward the camera (camera at the origin).
  glm::dvec3 n(0, -std::sin(a), std::cos(a));
  if (glm::dot(n, mu) > 0) n = -n;
  const std::size_t P = r.gb.pixels();
  int checked = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const std::size_t p = std::size_t(y) * cam.width + x;
      const double A = r.gb.alpha[p];
      if (A < 0.05) continue;
      ++checked;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.gb.normal[c * P + p] / A, n[c], 1e-6);
      // Exact intersection of the pixel's ray with the disk plane (ray d with d.z = 1: t = z).
      const glm::dvec3 d((x + 0.5 - cam.cx) / cam.fx, (y + 0.5 - cam.cy) / cam.fy, 1.0);
      const double z_true = glm::dot(n, mu) / glm::dot(n, d);
      const glm::dvec2 off(x + 0.5 - r.st.means2d[0], y + 0.5 - r.st.means2d[1]);
      const double r2 = glm::dot(off, off) / (cam.fx * cam.fx);  // squared angular offset
      EXPECT_NEAR(r.gb.depth[p] / A, z_true, 1e-6 + 1.0 * r2 * mu.z) << "pixel " << x << "," << y;
      EXPECT_NEAR(r.gb.median_depth[p], r.gb.depth[p] / A, 1e-9);
      EXPECT_NEAR(r.gb.extras[p], A, 1e-12);  // extras of 1 blend to alpha
    }
  EXPECT_GT(checked, 50);
  // Exactly at the centre the plane passes through the centre depth.
  EXPECT_NEAR(r.st.depths[0], mu.z, 1e-12);
}

// Median depth: the depth of the Gaussian during which T falls to 0.5 or below.
TEST(RasterBasics, MedianDepthRule) {
  const Camera cam = front_camera(32, 32, 40.f);
  const std::size_t centre = 16 * 32 + 16;
  // Front alpha 0.3 (T 0.7 after it), back alpha 0.5 (T 0.35): the median is the back one.
  {
    const double l0 = std::log(0.3 / 0.7), l1 = 0.0;
    const Render r = render(scene_of({{0, 0, 2.0}, {0, 0, 4.0}}, {l0, l1}, 0.5), cam);
    EXPECT_NEAR(r.gb.median_depth[centre], 4.0, 0.05);
  }
  // Front alpha 0.6: it already takes T below 0.5.
  {
    const double l0 = std::log(0.6 / 0.4);
    const Render r = render(scene_of({{0, 0, 2.0}, {0, 0, 4.0}}, {l0, 0.0}, 0.5), cam);
    EXPECT_NEAR(r.gb.median_depth[centre], 2.0, 0.05);
  }
}

TEST(RasterBasics, BackgroundAndEmptyScenes) {
  RasterSettings rs;
  rs.background = glm::vec3(0.25f, 0.5f, 0.75f);
  const Camera cam = front_camera(40, 20);
  for (const RasterScene<double>& sc :
       {scene_of({}, {}, 0.1), scene_of({{0, 0, -2.0}}, {2.0}, 0.3) /* behind the camera */}) {
    const Render r = render(sc, cam, rs);
    const std::size_t P = r.gb.pixels();
    for (std::size_t p = 0; p < P; ++p) {
      for (int c = 0; c < 3; ++c) ASSERT_DOUBLE_EQ(r.gb.color[c * P + p], double(rs.background[c]));
      ASSERT_EQ(r.gb.alpha[p], 0.0);
      ASSERT_EQ(r.gb.depth[p], 0.0);
      ASSERT_EQ(r.gb.median_depth[p], 0.0);
      ASSERT_EQ(r.st.median_index[p], kNoContributor);
    }
  }
}

// The float path (production) agrees with the double path (the gradient tests' reference).
TEST(RasterBasics, FloatMatchesDouble) {
  std::mt19937 rng(9);
  test::SceneSpec spec;
  spec.count = 300;
  spec.n_extras = 2;
  spec.scale_lo = 0.03f;
  spec.scale_hi = 0.15f;
  const RasterScene<double> sd = test::random_scene<double>(rng, spec);
  RasterScene<float> sf;
  sf.count = sd.count, sf.sh_degree = sd.sh_degree, sf.n_extras = sd.n_extras;
  auto cvt = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
  sf.positions = cvt(sd.positions), sf.log_scales = cvt(sd.log_scales), sf.rotations = cvt(sd.rotations);
  sf.opacity_logits = cvt(sd.opacity_logits), sf.sh = cvt(sd.sh), sf.extras = cvt(sd.extras);
  sf.filter3d = cvt(sd.filter3d);
  const Camera cam = test::random_camera(rng, 80, 60, 80.f, 4.f);
  GBufferT<double> gd;
  RasterStateT<double> std_;
  raster::forward_cpu(sd.view(), cam, RasterSettings::mip_splatting(), gd, std_);
  GBufferT<float> gf;
  RasterStateT<float> stf;
  raster::forward_cpu(sf.view(), cam, RasterSettings::mip_splatting(), gf, stf);
  auto close = [](const Buffer<float>& f, const Buffer<double>& d, double tol) {
    double num = 0, den = 0;
    for (std::size_t i = 0; i < d.size(); ++i) num += (f[i] - d[i]) * (f[i] - d[i]), den += d[i] * d[i];
    return std::sqrt(num / std::max(den, 1e-30)) < tol;
  };
  EXPECT_TRUE(close(gf.color, gd.color, 1e-4));
  EXPECT_TRUE(close(gf.alpha, gd.alpha, 1e-4));
  EXPECT_TRUE(close(gf.depth, gd.depth, 1e-4));
  EXPECT_TRUE(close(gf.normal, gd.normal, 1e-4));
  EXPECT_TRUE(close(gf.extras, gd.extras, 1e-4));
  EXPECT_TRUE(close(gf.median_depth, gd.median_depth, 1e-3));
}

TEST(RasterBasics, BadInputIsAnError) {
  std::vector<float> pos = {0, 0, 3}, ls = {-2, -2, -2}, rot = {1, 0, 0, 0}, op = {0}, sh(48, 0.f);
  GaussianView v;
  v.count = 1, v.positions = pos.data(), v.log_scales = ls.data(), v.rotations = rot.data();
  v.opacity_logits = op.data(), v.sh = sh.data();
  const Camera good = front_camera();
  EXPECT_NO_THROW(rasterize(v, good, RasterSettings{}, Device::CPU));
  Camera c = good;
  c.width = 0;
  EXPECT_THROW(rasterize(v, c, RasterSettings{}, Device::CPU), Error);
  c = good;
  c.fx = 0;
  EXPECT_THROW(rasterize(v, c, RasterSettings{}, Device::CPU), Error);
  c = good;
  c.dist.k1 = 0.1f;
  EXPECT_THROW(rasterize(v, c, RasterSettings{}, Device::CPU), Error);
  GaussianView b = v;
  b.sh_degree = 4;
  EXPECT_THROW(rasterize(b, good, RasterSettings{}, Device::CPU), Error);
  b = v;
  b.positions = nullptr;
  EXPECT_THROW(rasterize(b, good, RasterSettings{}, Device::CPU), Error);
  b = v;
  b.n_extras = 2;  // declared but missing
  EXPECT_THROW(rasterize(b, good, RasterSettings{}, Device::CPU), Error);
  b.n_extras = 17;
  EXPECT_THROW(rasterize(b, good, RasterSettings{}, Device::CPU), Error);
  // The backward pass refuses a view that does not match its forward pass.
  const RasterOutput out = rasterize(v, good, RasterSettings{}, Device::CPU);
  b = v;
  b.count = 0;
  EXPECT_THROW(rasterize_backward(b, out.state, GBufferGrad{}, GaussianGradView{}), Error);
  if (!cuda_compiled()) {
    EXPECT_THROW(rasterize(v, good, RasterSettings{}, Device::CUDA), Error);
  }
  try {
    c = good;
    c.width = -3;
    rasterize(v, c, RasterSettings{}, Device::CPU);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rasterizer"), std::string::npos) << e.what();
  }
}
