// The intrinsic trainer's material losses over a few steps on the floor-and-blob scene: when the warm-up
// runs them (each loss's formula and gradient are checked on their own in test_intrinsic_losses.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "core/scene/gaussians.h"
#include "tests/support/intrinsic_scene.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/trainer.h"

using namespace goris;
using namespace goris::test;

TEST(IntrinsicRenderer, MaterialLossesCanWaitForTheShadingPhase) {
  // intrinsic_material_losses_in_warmup=false: no region loss and no smoothness in the radiance warm-up
  // (iterations 1..shading_from), both from the first shaded iteration on; the label loss runs throughout.
  TrainConfig cfg = intrinsic_config(8);
  cfg.intrinsic.warmup = 4;
  cfg.densify.from_iter = 1 << 30;
  cfg.densify.until_iter = 0;
  cfg.densify.opacity_reset_interval = 1 << 30;
  ASSERT_EQ(cfg.shading_from(), 4);
  const std::vector<TrainView> views = shaded_views(cfg, floor_and_blob(4));
  auto run = [&](bool in_warmup) {
    TrainConfig c = cfg;
    c.intrinsic.material_losses_in_warmup = in_warmup;
    auto renderer = std::make_shared<IntrinsicRenderer>(c, 3.0f, Device::CPU);
    Trainer t(c, views, 3.0f, renderer, Trainer::initial_state(c, perturbed_start()));
    std::vector<StepStats> steps;
    while (!t.finished()) steps.push_back(t.step());
    return steps;
  };
  const std::vector<StepStats> waiting = run(false), always = run(true);
  ASSERT_EQ(waiting.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    const bool shaded = i + 1 > cfg.shading_from();
    EXPECT_EQ(waiting[i].smoothness > 0, shaded) << "iteration " << i + 1;
    EXPECT_EQ(waiting[i].region > 0, shaded) << "iteration " << i + 1;
    EXPECT_GT(waiting[i].label, 0.0) << "iteration " << i + 1;
    EXPECT_GT(always[i].smoothness, 0.0) << "iteration " << i + 1;
    EXPECT_GT(always[i].region, 0.0) << "iteration " << i + 1;
  }
  // The same first step apart from the skipped terms: the photo loss does not depend on the switch.
  EXPECT_DOUBLE_EQ(waiting[0].l1, always[0].l1);
  EXPECT_LT(waiting[0].loss, always[0].loss);
}

