// The training kernels on CUDA against the CPU reference on the same inputs: extras activation and its
// chain rule, Adam, the densification statistic, the finite check, densification round trips, and a few
// whole training steps. Skipped (with a message) where no CUDA device is present.
#include <cmath>
#include <random>
#include <vector>

#include "core/compute/finite_check.h"
#include "core/compute/memory.h"
#include "tests/support/test_support.h"
#include "train/loop/trainer.h"
#include "train/optimizer/adam.h"
#include "train/optimizer/densify.h"
#include "train/radiance/raster_renderer.h"

using namespace goris;

namespace {

GaussianModel random_model(size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  GaussianModel m(Device::CPU);
  m.allocate(n);
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    for (size_t i = 0; i < t.value.size(); ++i) {
      t.value[i] = u(rng);
      t.grad[i] = 0.1f * u(rng);
    }
  }
  return m;
}

void expect_close(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_NEAR(a[i], b[i], 1e-4f * std::max(1.0f, std::abs(a[i]))) << what << " element " << i;
}

}  // namespace

TEST(TrainCuda, ExtrasAdamStatsAndFiniteCheckMatchTheCpu) {
  GORIS_REQUIRE_GPU();
  GaussianModel cpu = random_model(5000, 1);
  GaussianModel gpu = cpu.copy_to(Device::CUDA);
  const GaussianView vc = cpu.view(true), vg = gpu.view(true);
  Buffer<float> act(5000 * extra::kCount, Device::CUDA);
  device_copy(act.data(), Device::CUDA, vg.extras, Device::CUDA, act.bytes());
  expect_close(act.to_host(), std::vector<float>(vc.extras, vc.extras + 5000 * extra::kCount), "activated extras");
  GaussianGradView gc = cpu.grad_view(true), gg = gpu.grad_view(true);
  std::vector<float> upstream(5000 * extra::kCount);
  for (size_t i = 0; i < upstream.size(); ++i) upstream[i] = std::sin(float(i));
  std::copy(upstream.begin(), upstream.end(), gc.extras);
  device_copy(gg.extras, Device::CUDA, upstream.data(), Device::CPU, upstream.size() * sizeof(float));
  cpu.backprop_extras();
  gpu.backprop_extras();
  expect_close(gpu.tensor(Param::ExtraLogit).grad.to_host(), cpu.tensor(Param::ExtraLogit).grad.to_host(), "extras grad");

  cpu.derive_diffuse_from_sh();
  gpu.derive_diffuse_from_sh();
  expect_close(gpu.tensor(Param::ExtraLogit).value.to_host(), cpu.tensor(Param::ExtraLogit).value.to_host(),
               "diffuse from SH");

  GaussianAdam ac, ag;
  for (int k = 0; k < 3; ++k)
    for (int g = 0; g < kGroupCount; ++g) {
      ac.step(cpu, ParamGroup(g), 0.01f);
      ag.step(gpu, ParamGroup(g), 0.01f);
    }
  for (int p = 0; p < kParamCount; ++p) {
    expect_close(gpu.tensor(Param(p)).value.to_host(), cpu.tensor(Param(p)).value.to_host(), param_name(Param(p)));
    expect_close(gpu.tensor(Param(p)).adam_v.to_host(), cpu.tensor(Param(p)).adam_v.to_host(), param_name(Param(p)));
  }

  DensifyStats sc, sg;
  sc.reset(5000, Device::CPU);
  sg.reset(5000, Device::CUDA);
  std::vector<float> norms(5000);
  std::vector<std::int32_t> radii(5000);
  for (int i = 0; i < 5000; ++i) {
    norms[i] = float(i % 17) * 0.01f;
    radii[i] = i % 3 == 0 ? 0 : i % 29;
  }
  Buffer<float> ng(norms, Device::CUDA);
  Buffer<std::int32_t> rg(radii, Device::CUDA);
  for (int k = 0; k < 2; ++k) {
    sc.add_view(norms.data(), radii.data(), 50.0f, 5000, Device::CPU);
    sg.add_view(ng.data(), rg.data(), 50.0f, 5000, Device::CUDA);
  }
  expect_close(sg.grad_accum.to_host(), sc.grad_accum.to_host(), "grad_accum");
  expect_close(sg.denom.to_host(), sc.denom.to_host(), "denom");
  expect_close(sg.max_radii.to_host(), sc.max_radii.to_host(), "max_radii");

  std::vector<float> v(300000, 1.0f);
  v[123456] = NAN;
  Buffer<float> vg2(v, Device::CUDA);
  EXPECT_EQ(first_non_finite(vg2.data(), v.size(), Device::CUDA), 123456u);

  // Densification makes a round trip through host memory: same result as on the CPU.
  const DensifySettings ds;
  densify_and_prune(cpu, sc, ds, 2.0f, true, 3);
  densify_and_prune(gpu, sg, ds, 2.0f, true, 3);
  ASSERT_EQ(gpu.count(), cpu.count());
  EXPECT_EQ(gpu.device(), Device::CUDA);
  expect_close(gpu.tensor(Param::Position).value.to_host(), cpu.tensor(Param::Position).value.to_host(), "positions");
}

TEST(TrainCuda, TrainingStepsFollowTheCpu) {
  GORIS_REQUIRE_GPU();
  TrainConfig config;
  config.iterations = 20;
  config.sh.max_degree = 1;
  config.sh.degree_interval = 10;
  config.anti_aliasing.filter_3d = true;
  config.densify.from_iter = 1 << 30;
  std::vector<TrainView> views;
  GaussianModel m = random_model(300, 2);
  for (size_t i = 0; i < m.count(); ++i) {
    for (int a = 0; a < 3; ++a) m.values(Param::LogScale)[i * 3 + a] = std::log(0.1f);
    m.values(Param::Rotation)[i * 4] += 2.0f;
  }
  for (int k = 0; k < 3; ++k) {
    TrainView v;
    v.name = "v" + std::to_string(k);
    Camera& c = v.camera;
    c.width = c.height = 64;
    c.fx = c.fy = 60;
    c.cx = c.cy = 32;
    const float a = 2.1f * k;
    const glm::vec3 eye(4 * std::cos(a), 4 * std::sin(a), 0.5f), z = glm::normalize(-eye);
    const glm::vec3 x = glm::normalize(glm::cross(z, glm::vec3(0, 0, 1))), y = glm::cross(z, x);
    for (int r = 0; r < 3; ++r) {
      c.R[r][0] = x[r];
      c.R[r][1] = y[r];
      c.R[r][2] = z[r];
    }
    c.t = -(c.R * eye);
    v.image.assign(3 * 64 * 64, 0.0f);
    for (size_t p = 0; p < v.image.size(); ++p) v.image[p] = 0.5f + 0.4f * std::sin(0.01f * float(p) + float(k));
    views.push_back(std::move(v));
  }
  auto rc = std::make_shared<RasterRenderer>(RasterRenderer::settings_for(config), Device::CPU);
  auto rg = std::make_shared<RasterRenderer>(RasterRenderer::settings_for(config), Device::CUDA);
  Trainer tc(config, views, 4.0f, rc, Trainer::initial_state(config, m.copy_to(Device::CPU)));
  Trainer tg(config, views, 4.0f, rg, Trainer::initial_state(config, m.copy_to(Device::CUDA)));
  while (!tc.finished()) {
    const StepStats a = tc.step(), b = tg.step();
    EXPECT_NEAR(a.loss, b.loss, 1e-3 * std::max(1.0, a.loss));
  }
  const auto pc = tc.model().tensor(Param::Position).value.to_host();
  const auto pg = tg.model().tensor(Param::Position).value.to_host();
  for (size_t i = 0; i < pc.size(); ++i) EXPECT_NEAR(pc[i], pg[i], 1e-3f) << i;
}
