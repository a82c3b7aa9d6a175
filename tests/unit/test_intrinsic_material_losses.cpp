// The intrinsic trainer's material losses over a few steps on the floor-and-blob scene: when the warm-up
// runs them, and what the rough-side roughness losses do to the materials (each loss's formula and
// gradient are checked on their own in test_intrinsic_losses.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/train/trainer.h"
#include "render/intrinsic/intrinsic_renderer.h"
#include "tests/support/intrinsic_scene.h"

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

namespace {

// Six intrinsic steps on floor_and_blob without densification, from perturbed_start(); `set` adjusts the
// config. Returns the first step's stats and the mean roughness of the final Gaussians whose region
// weight passes `keep` (every Gaussian when null).
std::pair<StepStats, double> six_steps_mean_roughness(const std::function<void(TrainConfig&)>& set,
                                                      bool glossy_masks, bool (*keep)(double region) = nullptr) {
  TrainConfig c = intrinsic_config(6);
  c.densify.from_iter = 1 << 30;
  c.densify.until_iter = 0;
  c.densify.opacity_reset_interval = 1 << 30;
  std::vector<TrainView> views = shaded_views(c, floor_and_blob(4));
  if (!glossy_masks)
    for (TrainView& v : views) v.glossy_mask.clear();
  set(c);
  auto renderer = std::make_shared<IntrinsicRenderer>(c, 3.0f, Device::CPU);
  Trainer t(c, views, 3.0f, renderer, Trainer::initial_state(c, perturbed_start()));
  const StepStats first = t.step();
  while (!t.finished()) t.step();
  const GaussianModel& m = t.model();
  const std::vector<float> ex = m.tensor(Param::ExtraLogit).value.to_host();
  auto sigmoid = [](float x) { return 1.0 / (1.0 + std::exp(-double(x))); };
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < m.count(); ++i) {
    if (keep && !keep(sigmoid(ex[i * extra::kCount + extra::kRegion]))) continue;
    sum += sigmoid(ex[i * extra::kCount + extra::kRoughness]);
    ++count;
  }
  EXPECT_GT(count, 0u) << "no Gaussian passed the region filter";
  return {first, sum / double(std::max<std::size_t>(count, 1))};
}

}  // namespace

TEST(IntrinsicRenderer, RoughnessRoughLossRaisesRoughnessOffTheGlossyMask) {
  // intrinsic_roughness_rough: mean((1 - M_gt)(alpha - R)) adds to the region term and, over a few steps,
  // raises the roughness of the Gaussians the non-glossy pixels see more than training without it does.
  auto run = [](float weight) {
    return six_steps_mean_roughness([&](TrainConfig& c) { c.intrinsic.roughness_rough = weight; }, true);
  };
  const auto [off, r_off] = run(0.0f);
  const auto [on, r_on] = run(1.0f);
  EXPECT_GT(on.region, off.region);
  EXPECT_DOUBLE_EQ(on.l1, off.l1);
  EXPECT_GT(r_on, r_off + 1e-4);
}

TEST(IntrinsicRenderer, RoughnessFollowsTheRenderedRegionWithoutGlossyMasks) {
  // intrinsic_roughness_follows_region: mean(M (alpha - R)) with the rendered region M held constant. It
  // needs no glossy mask (the views here have none), raises the roughness of the Gaussians the model
  // shades as rough (M > 0.5) and leaves the photo loss of the first step alone.
  auto run = [](float weight) {
    return six_steps_mean_roughness([&](TrainConfig& c) { c.intrinsic.roughness_follows_region = weight; }, false,
                                    [](double region) { return region > 0.5; });
  };
  const auto [off, r_off] = run(0.0f);
  const auto [on, r_on] = run(1.0f);
  EXPECT_EQ(off.region, 0.0);  // no glossy mask: no other region term
  EXPECT_GT(on.region, 0.0);
  EXPECT_DOUBLE_EQ(on.l1, off.l1);
  EXPECT_GT(r_on, r_off + 1e-3);
}
