// Intrinsic training on CUDA (rasterize, trace, filter, shade and back, densification included): two runs
// from the same start end identical bit for bit - model, Adam moments, environment map and net - now that
// no gradient sum uses atomics; and the losses follow the CPU's until the first densification. Skips
// without a GPU.
#include <algorithm>
#include <memory>
#include <vector>

#include "tests/support/intrinsic_scene.h"
#include "tests/support/model_values.h"
#include "tests/support/test_support.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/trainer.h"

using namespace goris;
using namespace goris::test;

namespace {

struct Trained {
  std::vector<float> model;
  std::string own_state;
  std::vector<double> losses;
};

Trained train(const TrainConfig& cfg, const std::vector<TrainView>& views, Device d) {
  auto renderer = std::make_shared<IntrinsicRenderer>(cfg, 3.0f, d);
  Trainer t(cfg, views, 3.0f, renderer, Trainer::initial_state(cfg, perturbed_start().copy_to(d)));
  Trained out;
  while (!t.finished()) out.losses.push_back(t.step().loss);
  out.model = all_values(t.model());
  out.own_state = renderer->save_own_state();
  return out;
}

}  // namespace

TEST(IntrinsicCuda, TrainingRepeatsBitForBitAndFollowsTheCpu) {
  GORIS_REQUIRE_GPU();
  const TrainConfig cfg = densifying_intrinsic_config();
  const std::vector<TrainView> views = shaded_views(cfg, floor_and_blob(4));
  TrainConfig cuda_cfg = cfg;
  cuda_cfg.device = DeviceChoice::CUDA;
  const Trained a = train(cuda_cfg, views, Device::CUDA), b = train(cuda_cfg, views, Device::CUDA);
  EXPECT_EQ(a.losses, b.losses);
  EXPECT_EQ(a.model, b.model);
  EXPECT_TRUE(a.own_state == b.own_state) << "environment map / net differ";
  const Trained c = train(cfg, views, Device::CPU);
  ASSERT_EQ(a.losses.size(), c.losses.size());
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_NEAR(a.losses[i], c.losses[i], 1e-3 * std::max(1.0, c.losses[i])) << "iteration " << i + 1;
}
