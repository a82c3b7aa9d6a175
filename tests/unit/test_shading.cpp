// Deferred shading behaviour: a mirror in front of a constant environment shows it, M = 1 leaves the SH
// colour untouched, only glossy surface pixels get rays, the ray geometry (depth along z, reflection), the
// traced-image fill values, the G-buffer adapter and the input checks.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "render/envmap/environment_map.h"
#include "render/shading/deferred_shading.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_shading_scene.h"

using namespace goris;
using namespace goris::test;

namespace {

// A float surface of W x H pixels, all alike (values per plane), on the CPU.
struct FlatSurface {
  int W = 5, H = 5;
  Camera cam;
  std::vector<float> color, alpha, depth, normal, region, f0, rough;
  FlatSurface(float D, float a, float z, glm::vec3 n_cam, float M, float F0, float r) {
    cam.width = W, cam.height = H, cam.fx = cam.fy = 5.0f, cam.cx = cam.cy = 2.5f;
    const std::size_t P = std::size_t(W) * H;
    color.assign(3 * P, D), alpha.assign(P, a), depth.assign(P, a * z), region.assign(P, a * M);
    f0.assign(3 * P, a * F0), rough.assign(P, a * r), normal.resize(3 * P);
    for (std::size_t p = 0; p < P; ++p)
      for (int c = 0; c < 3; ++c) normal[c * P + p] = a * n_cam[c];
  }
  SurfaceImages view() const {
    SurfaceImages s;
    s.width = W, s.height = H;
    s.color = color.data(), s.alpha = alpha.data(), s.depth = depth.data(), s.normal = normal.data();
    s.region = region.data(), s.f0 = f0.data(), s.roughness = rough.data();
    return s;
  }
  std::size_t P() const { return std::size_t(W) * H; }
};

Buffer<float> fbuf(std::size_t n, float v) { return Buffer<float>(std::vector<float>(n, v), Device::CPU); }

}  // namespace

TEST(Shading, MirrorShowsAConstantEnvironment) {
  EnvironmentMap env(8, Device::CPU, 0.6f);
  FlatSurface s(0.1f, 1.0f, 2.0f, glm::normalize(glm::vec3(0.1f, -0.2f, -1.0f)), 0.0f, 1.0f, 0.0f);
  const auto out = shade(s.cam, s.view(), fbuf(3 * s.P(), 0.0f), fbuf(s.P(), 1.0f), env.mips(), ShadingSettings{},
                         Device::CPU, true);
  for (std::size_t i = 0; i < 3 * s.P(); ++i) {
    EXPECT_NEAR(out.color[i], 0.7f, 1e-6f);
    EXPECT_NEAR(out.glossy[i], 0.6f, 1e-6f);
    EXPECT_NEAR(out.env_radiance[i], 0.6f, 1e-6f);
  }
}

TEST(Shading, RegionWeightOneReturnsTheShColourExactly) {
  ShadingScene d = ShadingScene::make(3, false);
  d.region = d.alpha;  // M = 1 everywhere
  const auto out = shade(d.cam, d.view(), Buffer<double>(d.L, Device::CPU), Buffer<double>(d.V, Device::CPU), d.env(),
                         ShadingSettings{}, Device::CPU);
  for (std::size_t i = 0; i < d.color.size(); ++i) EXPECT_EQ(out.color[i], d.color[i]);
}

TEST(Shading, OnlyGlossySurfacePixelsGetRays) {
  ShadingScene d = ShadingScene::make(4, false, true);  // pixel 1: M = 0.995, 7: M = 1, 10: alpha 0.3
  const auto rays = make_reflection_rays(d.cam, d.view(), ShadingSettings{}, Device::CPU);
  std::vector<std::uint32_t> expected;
  for (std::uint32_t p = 0; p < d.P(); ++p)
    if (p != 1 && p != 7 && p != 10) expected.push_back(p);
  EXPECT_EQ(rays.pixels.to_host(), expected);
  EXPECT_EQ(rays.origins.size(), 3 * expected.size());
  // A stricter threshold drops pixels whose M is above it.
  ShadingSettings strict;
  strict.glossy_max_region = 1e-6f;
  EXPECT_EQ(make_reflection_rays(d.cam, d.view(), strict, Device::CPU).count, 0u);
}

TEST(Shading, RayGeometryUsesDepthAlongZ) {
  // Identity camera: pixel (2, 2) looks along +z. A normal tilted 45 degrees reflects the ray to -y.
  FlatSurface s(0.0f, 0.8f, 3.0f, glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f)), 0.2f, 0.5f, 0.5f);
  ShadingSettings st;
  st.ray_offset = 0.1f;
  const auto rays = make_reflection_rays(s.cam, s.view(), st, Device::CPU);
  ASSERT_EQ(rays.count, s.P());
  const std::size_t i = 2 * 5 + 2;
  ASSERT_EQ(rays.pixels[i], i);
  EXPECT_NEAR(rays.directions[3 * i + 0], 0.0f, 1e-6f);
  EXPECT_NEAR(rays.directions[3 * i + 1], -1.0f, 1e-6f);
  EXPECT_NEAR(rays.directions[3 * i + 2], 0.0f, 1e-6f);
  EXPECT_NEAR(rays.origins[3 * i + 1], -0.1f, 1e-6f);
  EXPECT_NEAR(rays.origins[3 * i + 2], 3.0f, 1e-5f);  // depth / alpha, not the raw sum
  // A corner pixel: the surface point still has camera z = 3 although the ray is longer than 3.
  EXPECT_NEAR(rays.origins[2] - 0.1f * rays.directions[2], 3.0f, 1e-5f);
  // Translated camera: origins move with the centre.
  s.cam.t = glm::vec3(1.0f, 0.0f, 0.0f);  // centre at (-1, 0, 0)
  const auto moved = make_reflection_rays(s.cam, s.view(), st, Device::CPU);
  EXPECT_NEAR(moved.origins[3 * i], -1.0f, 1e-6f);
}

TEST(Shading, TracedImagesFillUntracedPixelsAndDivideOpaqueRays) {
  ShadingScene d = ShadingScene::make(6, false, true);
  const auto rays = make_reflection_rays(d.cam, d.view(), ShadingSettings{}, Device::CPU);
  const std::size_t n = rays.count;
  std::vector<double> color(3 * n, 0.5), alpha(n, 0.4);
  alpha[0] = 0.995;
  Buffer<double> L, V;
  traced_to_images(rays, d.W, d.H, Buffer<double>(color, Device::CPU), Buffer<double>(alpha, Device::CPU),
                   TracedImageSettings{}, L, V);
  const std::size_t P = d.P();
  EXPECT_EQ(V[1], 1.0);  // untraced: the environment unoccluded
  EXPECT_EQ(L[1], 0.0);
  const std::size_t p0 = rays.pixels[0], p1 = rays.pixels[1];
  EXPECT_EQ(V[p0], 0.0);  // opaque: divided, V = 0
  EXPECT_NEAR(L[P + p0], 0.5 / 0.995, 1e-12);
  EXPECT_NEAR(V[p1], 0.6, 1e-12);
  EXPECT_EQ(L[2 * P + p1], 0.5);
}

TEST(Shading, SurfaceFromGBufferPicksTheMaterialChannels) {
  GBufferT<float> g;
  g.width = 4, g.height = 3, g.n_extras = 6;
  const std::size_t P = g.pixels();
  g.color = Buffer<float>(3 * P), g.alpha = Buffer<float>(P), g.depth = Buffer<float>(P);
  g.normal = Buffer<float>(3 * P), g.extras = Buffer<float>(6 * P);
  const auto s = surface_from_gbuffer(g, MaterialChannels{5, 1, 0});
  EXPECT_EQ(s.region, g.extras.data() + 5 * P);
  EXPECT_EQ(s.f0, g.extras.data() + P);
  EXPECT_EQ(s.roughness, g.extras.data());
  EXPECT_THROW(surface_from_gbuffer(g, MaterialChannels{0, 4, 5}), Error);  // F0 needs 3 channels
  EXPECT_THROW(surface_from_gbuffer(g, MaterialChannels{6, 1, 4}), Error);
  g.depth = Buffer<float>(P - 1);
  EXPECT_THROW(surface_from_gbuffer(g, MaterialChannels{}), Error);
}

TEST(Shading, BadInputIsRejected) {
  EnvironmentMap env(4, Device::CPU);
  FlatSurface s(0.1f, 1.0f, 2.0f, glm::vec3(0, 0, -1), 0.0f, 0.5f, 0.5f);
  const std::size_t P = s.P();
  const auto L = fbuf(3 * P, 0.0f), V = fbuf(P, 1.0f);
  auto expect_error = [](const std::function<void()>& f, const std::string& needle) {
    try {
      f();
      ADD_FAILURE() << "no error (expected one mentioning '" << needle << "')";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  const ShadingSettings st;
  // Wrong sizes.
  expect_error([&] { shade(s.cam, s.view(), fbuf(P, 0.0f), V, env.mips(), st, Device::CPU); }, "L_ind");
  expect_error([&] { shade(s.cam, s.view(), L, fbuf(P + 1, 1.0f), env.mips(), st, Device::CPU); }, "visibility");
  Camera wrong = s.cam;
  wrong.width = 7;
  expect_error([&] { make_reflection_rays(wrong, s.view(), st, Device::CPU); }, "camera");
  // NaN in an input plane.
  s.depth[3] = std::nanf("");
  expect_error([&] { make_reflection_rays(s.cam, s.view(), st, Device::CPU); }, "depth");
  s.depth[3] = 2.0f;
  s.f0[5] = INFINITY;
  expect_error([&] { shade(s.cam, s.view(), L, V, env.mips(), st, Device::CPU); }, "F0");
  s.f0[5] = 0.5f;
  auto nanL = fbuf(3 * P, 0.0f);
  nanL[4] = std::nanf("");
  expect_error([&] { shade(s.cam, s.view(), nanL, V, env.mips(), st, Device::CPU); }, "L_ind");
  // Missing planes, bad settings, empty environment.
  SurfaceImages missing = s.view();
  missing.normal = nullptr;
  expect_error([&] { make_reflection_rays(s.cam, missing, st, Device::CPU); }, "normal");
  ShadingSettings bad;
  bad.ray_offset = -1.0f;
  expect_error([&] { make_reflection_rays(s.cam, s.view(), bad, Device::CPU); }, "ray_offset");
  expect_error([&] { shade(s.cam, s.view(), L, V, envmap::CubeMipsT<float>{}, st, Device::CPU); }, "environment");
  // Traced results that do not match the rays.
  const auto rays = make_reflection_rays(s.cam, s.view(), st, Device::CPU);
  Buffer<float> Li, Vi;
  expect_error([&] { traced_to_images(rays, s.W, s.H, fbuf(rays.count, 0.f), fbuf(rays.count, 0.f), {}, Li, Vi); },
               "traced colour");
  // Backends.
  ShadingScene d = ShadingScene::make(1, false);
  expect_error([&] { make_reflection_rays(d.cam, d.view(), ShadingSettings{}, Device::CUDA); }, "CPU only");
  if (!cuda_compiled())
    expect_error([&] { make_reflection_rays(s.cam, s.view(), st, Device::CUDA); }, "CUDA");
}
