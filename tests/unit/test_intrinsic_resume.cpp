// An intrinsic run resumed from a checkpoint ends bit for bit where the uninterrupted run does, from any
// iteration: between emit-weight refreshes, right after a densification, before and after one.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "tests/support/intrinsic_scene.h"
#include "tests/support/model_values.h"
#include "tests/support/test_support.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/checkpoint.h"
#include "train/loop/trainer.h"

using namespace goris;
using namespace goris::test;

TEST(IntrinsicResume, FromAnyCheckpointIsBitExact) {
  const TrainConfig cfg = densifying_intrinsic_config();
  const std::vector<TrainView> views = shaded_views(cfg, floor_and_blob(4));
  auto straight_renderer = std::make_shared<IntrinsicRenderer>(cfg, 3.0f, Device::CPU);
  Trainer straight(cfg, views, 3.0f, straight_renderer, Trainer::initial_state(cfg, perturbed_start()));
  while (!straight.finished()) straight.step();

  const auto dir = test::scratch_dir("intrinsic_resume");
  for (const int stop_at : {5, 7, 13, 19}) {
    auto first_renderer = std::make_shared<IntrinsicRenderer>(cfg, 3.0f, Device::CPU);
    Trainer first(cfg, views, 3.0f, first_renderer, Trainer::initial_state(cfg, perturbed_start()));
    for (int i = 0; i < stop_at; ++i) first.step();
    const auto file = dir / ("at_" + std::to_string(stop_at) + ".ckpt");
    first.save_checkpoint(file);

    Checkpoint ck = read_checkpoint(file, Device::CPU);
    auto renderer = std::make_shared<IntrinsicRenderer>(ck.config, 3.0f, Device::CPU);
    Trainer::load_renderer_state(file, *renderer);
    Trainer resumed(ck.config, views, 3.0f, renderer, std::move(ck.state));
    while (!resumed.finished()) resumed.step();
    EXPECT_EQ(all_values(resumed.model()), all_values(straight.model())) << "resumed after iteration " << stop_at;
    EXPECT_TRUE(renderer->save_own_state() == straight_renderer->save_own_state())
        << "environment map / net differ, resumed after iteration " << stop_at;
  }
}
