// Finite-difference checks in double precision of deferred shading's backward passes: the combine with
// respect to every input (D, M, F0, roughness, normal, alpha, depth, L_ind', V', the environment texels),
// the reflection-ray construction (depth, alpha, normal) and the traced-results-to-images step (with and
// without the authors' division by alpha on opaque rays).
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "render/shading/deferred_shading.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_shading_scene.h"

using namespace goris;
using namespace goris::test;

namespace {

constexpr double kH = 1e-6;

Buffer<double> buf(const std::vector<double>& v) { return Buffer<double>(v, Device::CPU); }
std::vector<double> host(const Buffer<double>& b) { return b.to_host(); }

// Central difference of f with respect to each element of `x` against `analytic`.
void check_fd(const std::string& what, std::vector<double>& x, const std::vector<double>& analytic,
              const std::function<double()>& f, double tol = 1e-6) {
  ASSERT_EQ(x.size(), analytic.size()) << what;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double x0 = x[i];
    x[i] = x0 + kH;
    const double fp = f();
    x[i] = x0 - kH;
    const double fm = f();
    x[i] = x0;
    const double fd = (fp - fm) / (2 * kH);
    EXPECT_NEAR(fd, analytic[i], tol * (1 + std::abs(fd))) << what << "[" << i << "]";
  }
}

struct SurfaceGradBuffers {
  std::vector<double> color, alpha, depth, normal, region, f0, rough;
  explicit SurfaceGradBuffers(std::size_t P)
      : color(3 * P), alpha(P), depth(P), normal(3 * P), region(P), f0(3 * P), rough(P) {}
  SurfaceGradsT<double> view() {
    return {color.data(), alpha.data(), depth.data(), normal.data(), region.data(), f0.data(), rough.data()};
  }
};

// env_radius > 0: the environment on a sphere around the camera (every surface point inside it), so the
// lookup direction also depends on the surface point, hence on depth and alpha.
void check_combine(unsigned seed, bool mirror_f0, bool normalize, float env_radius = 0.0f) {
  ShadingScene s = ShadingScene::make(seed, mirror_f0, true);
  if (mirror_f0 && !normalize) s.f0.assign(s.f0.size(), 1.0);  // F0 = 1 without the division as well
  ShadingSettings st;
  st.normalize_materials = normalize;
  const glm::vec3 cam_centre = s.cam.center();
  for (int c = 0; c < 3; ++c) st.env_center[c] = cam_centre[c] + 0.3f * float(c) - 0.2f;
  st.env_radius = env_radius;
  const auto w = random_weights(3 * s.P(), seed + 100);
  auto loss = [&] {
    const auto out = shade(s.cam, s.view(), buf(s.L), buf(s.V), s.env(), st, Device::CPU);
    return dot(host(out.color), w);
  };
  SurfaceGradBuffers g(s.P());
  Buffer<double> dL, dV;
  std::vector<double> genv(s.chain.size(), 0.0);
  shade_backward(s.cam, s.view(), buf(s.L), buf(s.V), s.env(), st, buf(w), g.view(), dL, dV, genv.data(), Device::CPU);
  const std::string tag = std::string(mirror_f0 ? "mirror " : "") + (normalize ? "normalized " : "raw ") +
                          (env_radius > 0 ? "sphere " : "");
  check_fd(tag + "D", s.color, g.color, loss);
  check_fd(tag + "M", s.region, g.region, loss);
  check_fd(tag + "roughness", s.rough, g.rough, loss);
  check_fd(tag + "alpha", s.alpha, g.alpha, loss);
  check_fd(tag + "depth", s.depth, g.depth, loss);  // at infinity zero: depth only moves the ray origins
  if (env_radius > 0) {  // on the sphere the surface point moves the lookup
    double largest = 0;
    for (double v : g.depth) largest = std::max(largest, std::abs(v));
    EXPECT_GT(largest, 1e-3) << tag;
  }
  check_fd(tag + "L_ind'", s.L, host(dL), loss);
  check_fd(tag + "V'", s.V, host(dV), loss);
  check_fd(tag + "env texels", s.chain, genv, loss);
  if (mirror_f0)
    check_fd(tag + "normal", s.normal, g.normal, loss);  // Schlick's weight drops out with F0 = 1
  else
    check_fd(tag + "F0", s.f0, g.f0, loss);
}

}  // namespace

TEST(ShadingGradients, CombineWithRandomMaterials) { check_combine(1, false, true); }
TEST(ShadingGradients, CombineOnMirrorsIncludingTheNormal) { check_combine(2, true, true); }
TEST(ShadingGradients, CombineWithoutMaterialNormalisation) {
  check_combine(3, false, false);
  check_combine(4, true, false);
}
TEST(ShadingGradients, CombineWithTheEnvironmentOnASphere) {
  check_combine(5, false, true, 6.0f);
  check_combine(6, true, true, 6.0f);
  check_combine(7, true, false, 6.0f);
}

TEST(ShadingGradients, ReflectionRaysBackward) {
  ShadingScene s = ShadingScene::make(5, false, true);
  ShadingSettings st;
  st.ray_offset = 0.3f;
  const auto rays0 = make_reflection_rays(s.cam, s.view(), st, Device::CPU);
  ASSERT_EQ(rays0.count, s.P() - 3);  // the three rough / empty pixels are skipped
  const auto wo = random_weights(3 * rays0.count, 6), wd = random_weights(3 * rays0.count, 7);
  auto loss = [&] {
    const auto r = make_reflection_rays(s.cam, s.view(), st, Device::CPU);
    EXPECT_EQ(r.count, rays0.count);
    return dot(host(r.origins), wo) + dot(host(r.directions), wd);
  };
  SurfaceGradBuffers g(s.P());
  reflection_rays_backward(s.cam, s.view(), st, rays0, wo.data(), wd.data(), g.view(), Device::CPU);
  check_fd("rays depth", s.depth, g.depth, loss);
  check_fd("rays alpha", s.alpha, g.alpha, loss);
  check_fd("rays normal", s.normal, g.normal, loss);
  // Accumulation: a second backward doubles the gradients.
  const auto once = g.depth;
  reflection_rays_backward(s.cam, s.view(), st, rays0, wo.data(), wd.data(), g.view(), Device::CPU);
  for (std::size_t p = 0; p < s.P(); ++p) EXPECT_DOUBLE_EQ(g.depth[p], 2 * once[p]);
}

TEST(ShadingGradients, TracedImagesBackward) {
  ShadingScene s = ShadingScene::make(8, false, true);
  const auto rays = make_reflection_rays(s.cam, s.view(), ShadingSettings{}, Device::CPU);
  const std::size_t n = rays.count;
  std::vector<double> color = random_weights(3 * n, 9), alpha(n);
  for (auto& c : color) c = std::abs(c);
  for (std::size_t i = 0; i < n; ++i) alpha[i] = i % 3 == 0 ? 0.995 : 0.1 + 0.8 * double(i) / n;  // some opaque
  const auto wL = random_weights(3 * s.P(), 10), wV = random_weights(s.P(), 11);
  for (bool divide : {true, false}) {
    TracedImageSettings ts;
    ts.divide_opaque = divide;
    auto loss = [&] {
      Buffer<double> L, V;
      traced_to_images(rays, s.W, s.H, buf(color), buf(alpha), ts, L, V);
      return dot(host(L), wL) + dot(host(V), wV);
    };
    Buffer<double> dcolor, dalpha;
    traced_to_images_backward(rays, s.W, s.H, buf(color), buf(alpha), ts, buf(wL), buf(wV), dcolor, dalpha);
    const std::string tag = divide ? "divided " : "plain ";
    check_fd(tag + "traced colour", color, host(dcolor), loss);
    check_fd(tag + "traced alpha", alpha, host(dalpha), loss);
  }
}
