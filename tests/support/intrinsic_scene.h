#pragma once
// The intrinsic renderer's small test scene, shared by the CPU tests and the CUDA tests: a glossy floor
// under a rough blob, a short intrinsic configuration, three views shaded from the scene (with its region
// and label as glossy and object masks), and a perturbed start the training has to correct.
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/scene/gaussians.h"
#include "tests/support/test_scenes.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/trainer.h"

namespace goris::test {

inline float logit(float p) { return std::log(p / (1 - p)); }

// A glossy floor (a grid of flat Gaussians at z = 0, region weight ~0.05) and a rough coloured blob above
// it (region ~0.95) whose reflection the floor shows.
inline GaussianModel floor_and_blob(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  const int grid = 8, blob = 12, n = grid * grid + blob;
  GaussianModel m(Device::CPU);
  m.allocate(size_t(n));
  for (int i = 0; i < n; ++i) {
    const bool is_floor = i < grid * grid;
    float* p = m.values(Param::Position) + 3 * i;
    float* s = m.values(Param::LogScale) + 3 * i;
    if (is_floor) {
      p[0] = -1.0f + 2.0f * ((i % grid) + 0.5f) / grid;
      p[1] = -1.0f + 2.0f * ((i / grid) + 0.5f) / grid;
      p[2] = 0.0f;
      s[0] = s[1] = std::log(0.16f);
      s[2] = std::log(0.01f);
    } else {
      p[0] = 0.25f * u(rng);
      p[1] = 0.25f * u(rng);
      p[2] = 0.45f + 0.15f * u(rng);
      for (int a = 0; a < 3; ++a) s[a] = std::log(0.12f);
    }
    float* q = m.values(Param::Rotation) + 4 * i;
    q[0] = 1.0f;
    q[1] = 0.05f * u(rng);
    q[2] = 0.05f * u(rng);
    q[3] = 0.05f * u(rng);
    m.values(Param::OpacityLogit)[i] = is_floor ? 3.0f : 2.0f;
    float* sh = m.values(Param::Sh) + 48 * i;
    std::fill(sh, sh + 48, 0.0f);
    for (int c = 0; c < 3; ++c) sh[c] = is_floor ? -0.8f + 0.1f * u(rng) : 1.2f * u(rng);
    float* e = m.values(Param::ExtraLogit) + extra::kCount * i;
    for (int k = 0; k < extra::kCount; ++k) e[k] = 0.3f * u(rng);
    e[extra::kRegion] = logit(is_floor ? 0.05f : 0.95f);
    e[extra::kRoughness] = logit(is_floor ? 0.1f : 0.6f);
    for (int c = 0; c < 3; ++c) e[extra::kFresnel + c] = logit(is_floor ? 0.6f : 0.04f) + 0.2f * u(rng);
    e[extra::kLabel] = logit(is_floor ? 0.02f : 0.98f);
  }
  m.sh_degree = 0;
  m.max_sh_degree = 0;
  return m;
}

inline TrainConfig intrinsic_config(int iterations) {
  TrainConfig c;
  c.mode = TrainMode::Intrinsic;
  c.iterations = iterations;
  c.device = DeviceChoice::CPU;
  c.sh.max_degree = 0;
  c.anti_aliasing.filter_3d = false;
  c.intrinsic.env_resolution = 8;
  c.intrinsic.warmup = 0;
  c.bookkeeping.checkpoint_interval = 0;
  return c;
}

// 24 intrinsic iterations that densify at 6, 12 and 18 (a threshold every Gaussian passes): the repeatability
// tests' run.
inline TrainConfig densifying_intrinsic_config() {
  TrainConfig c = intrinsic_config(24);
  c.densify.from_iter = 6;
  c.densify.interval = 6;
  c.densify.until_iter = 18;
  c.densify.grad_threshold = 1e-6f;
  return c;
}

// Three views of `truth` shaded by the intrinsic renderer, with its region / label as glossy / object masks.
inline std::vector<TrainView> shaded_views(const TrainConfig& cfg, GaussianModel truth) {
  auto target_renderer = std::make_shared<IntrinsicRenderer>(cfg, 3.0f, Device::CPU);
  target_renderer->set_shading(true);
  std::vector<TrainView> views;
  const glm::vec3 eyes[3] = {{2.2f, -0.4f, 1.6f}, {-1.8f, 1.2f, 1.5f}, {0.3f, 2.2f, 1.7f}};
  for (int k = 0; k < 3; ++k) {
    TrainView v;
    v.name = "v" + std::to_string(k);
    v.camera = look_at(eyes[k], {0, 0, 0.1f}, 32, 55);
    const RenderedImages r = target_renderer->forward(truth.view(true), v.camera);
    const size_t hw = 32 * 32;
    v.image.assign(r.color, r.color + 3 * hw);
    v.glossy_mask.assign(hw, 0.0f);
    v.object_mask.assign(hw, 0.0f);
    for (size_t p = 0; p < hw; ++p) {  // the rendered region / label as masks
      v.glossy_mask[p] = r.extras[extra::kRegion * hw + p] < 0.5f && r.alpha[p] > 0.5f ? 1.0f : 0.0f;
      v.object_mask[p] = r.extras[extra::kLabel * hw + p] > 0.5f ? 1.0f : 0.0f;
    }
    views.push_back(std::move(v));
  }
  return views;
}

// floor_and_blob(4) with its colour and label off: what the training has to recover.
inline GaussianModel perturbed_start() {
  GaussianModel start = floor_and_blob(4);
  for (size_t i = 0; i < start.count(); ++i) {
    start.values(Param::Sh)[48 * i] += 0.3f;
    start.values(Param::ExtraLogit)[extra::kCount * i + extra::kLabel] = 0.0f;
  }
  return start;
}

}  // namespace goris::test
