// CUDA vs CPU agreement of the environment map and deferred shading (forward and backward), float, and
// the CUDA backward's repeatability.
// Skips where no CUDA device is present.
#include <cmath>
#include <vector>

#include "render/envmap/environment_map.h"
#include "render/shading/deferred_shading.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_shading_scene.h"

using namespace goris;
using namespace goris::test;

namespace {

std::vector<float> to_float(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

// The scene's planes as float Buffers on one device.
struct DeviceSurface {
  Buffer<float> color, alpha, depth, normal, region, f0, rough, L, V;
  int W, H;
  DeviceSurface(const ShadingScene& s, Device d)
      : color(to_float(s.color), d), alpha(to_float(s.alpha), d), depth(to_float(s.depth), d),
        normal(to_float(s.normal), d), region(to_float(s.region), d), f0(to_float(s.f0), d), rough(to_float(s.rough), d),
        L(to_float(s.L), d), V(to_float(s.V), d), W(s.W), H(s.H) {}
  SurfaceImages view() const {
    SurfaceImages v;
    v.width = W, v.height = H;
    v.color = color.data(), v.alpha = alpha.data(), v.depth = depth.data(), v.normal = normal.data();
    v.region = region.data(), v.f0 = f0.data(), v.roughness = rough.data();
    return v;
  }
};

void expect_close(const std::vector<float>& a, const std::vector<float>& b, float tol, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], tol * (1 + std::abs(a[i]))) << what << "[" << i << "]";
}

// env_radius > 0: the environment on a sphere around the camera (env_proxy_math.h).
void expect_cuda_agrees_with_cpu(float env_radius) {
  const ShadingScene s = ShadingScene::make(21, false, true);
  ShadingSettings st;
  const glm::vec3 cam_centre = s.cam.center();
  for (int c = 0; c < 3; ++c) st.env_center[c] = cam_centre[c] + 0.1f * float(c);
  st.env_radius = env_radius;
  std::vector<float> dC(3 * s.P());
  for (std::size_t i = 0; i < dC.size(); ++i) dC[i] = std::sin(0.7f * float(i));
  struct Result {
    std::vector<float> color, pixels_as_float, origins, dnormal, dalpha, dL, dV, env_grads;
  };
  auto run = [&](Device d) {
    EnvironmentMap env(16, d, 0.5f);
    std::vector<float> p(env.param_count());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0.3f * std::sin(0.1f * float(i));
    env.params().upload(p.data(), p.size());
    env.update();
    DeviceSurface ds(s, d);
    Result r;
    const auto rays = make_reflection_rays(s.cam, ds.view(), st, d);
    for (std::uint32_t px : rays.pixels.to_host()) r.pixels_as_float.push_back(float(px));
    r.origins = rays.origins.to_host();
    const auto out = shade(s.cam, ds.view(), ds.L, ds.V, env.mips(), st, d);
    r.color = out.color.to_host();
    Buffer<float> gnormal(3 * s.P(), d), galpha(s.P(), d), dL, dV;
    gnormal.fill_zero();
    galpha.fill_zero();
    SurfaceGrads g;
    g.normal = gnormal.data();
    g.alpha = galpha.data();
    shade_backward(s.cam, ds.view(), ds.L, ds.V, env.mips(), st, Buffer<float>(dC, d), g, dL, dV, env.mip_grads(), d);
    const Buffer<float> ones(std::vector<float>(3 * rays.count, 1.0f), d);
    reflection_rays_backward(s.cam, ds.view(), st, rays, ones.data(), ones.data(), g, d);
    env.backward();
    r.dnormal = gnormal.to_host(), r.dalpha = galpha.to_host(), r.dL = dL.to_host(), r.dV = dV.to_host();
    r.env_grads = env.grads().to_host();
    return r;
  };
  const Result cpu = run(Device::CPU), gpu = run(Device::CUDA);
  EXPECT_EQ(cpu.pixels_as_float, gpu.pixels_as_float);
  expect_close(cpu.origins, gpu.origins, 1e-5f, "origins");
  expect_close(cpu.color, gpu.color, 1e-5f, "colour");
  expect_close(cpu.dnormal, gpu.dnormal, 1e-4f, "d normal");
  expect_close(cpu.dalpha, gpu.dalpha, 1e-4f, "d alpha");
  expect_close(cpu.dL, gpu.dL, 1e-5f, "d L_ind");
  expect_close(cpu.dV, gpu.dV, 1e-5f, "d V");
  expect_close(cpu.env_grads, gpu.env_grads, 1e-4f, "env grads");
  // The texel gradients are summed in pixel order (deferred_texel_grads.h): a second run repeats them bit
  // for bit.
  const Result again = run(Device::CUDA);
  EXPECT_EQ(again.env_grads, gpu.env_grads);
  EXPECT_EQ(again.dnormal, gpu.dnormal);
}

}  // namespace

TEST(ShadingCuda, AgreesWithCpu) {
  GORIS_REQUIRE_GPU();
  expect_cuda_agrees_with_cpu(0.0f);
}

TEST(ShadingCuda, AgreesWithCpuWithTheEnvironmentOnASphere) {
  GORIS_REQUIRE_GPU();
  expect_cuda_agrees_with_cpu(6.0f);
}
