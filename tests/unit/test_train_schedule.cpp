// TrainConfig's schedule for runs of any length: the warm-up, the opacity resets, the colour's rate and the
// mirror-world prune, as functions of the iteration count (no training).
#include <cmath>

#include <gtest/gtest.h>

#include "core/util/error.h"
#include "train/config/train_config.h"

using namespace goris;

TEST(TrainConfig, ShortRunsKeepHalfOfThemselvesInTheWarmUp) {
  TrainConfig c;
  c.iterations = 30000;  // the paper's schedule as given
  EXPECT_EQ(c.shading_from(), 4000);
  EXPECT_EQ(c.shading_phase_iteration(10000), 10000);
  EXPECT_EQ(c.shading_phase_iteration(2000), 4000);
  c.iterations = 60000;  // longer runs keep the absolute warm-up
  EXPECT_EQ(c.shading_from(), 4000);
  c.iterations = 2000;  // scaled 267, but half the run: 1000
  EXPECT_EQ(c.shading_from(), 1000);
  // The shading phase's points follow: 10000 of [4000, 30000] is 6/26 of the way through [1000, 2000].
  EXPECT_EQ(c.shading_phase_iteration(10000), 1231);
  EXPECT_EQ(c.shading_phase_iteration(30000), 2000);
  EXPECT_EQ(c.shading_phase_iteration(4000), 1000);
  c.iterations = 8000;  // half the run is more than the warm-up itself: 4000
  EXPECT_EQ(c.shading_from(), 4000);
  c.intrinsic.warmup_min_fraction = 0;  // the paper's proportions
  c.iterations = 2000;
  EXPECT_EQ(c.shading_from(), 267);
  EXPECT_EQ(c.shading_phase_iteration(10000), 267 + 400);
  c.intrinsic.warmup_min_fraction = 1.5f;
  EXPECT_THROW(c.validate("config"), Error);
}

TEST(TrainConfig, OpacityResetsScaleWithTheDensificationWindow) {
  // The defaults: 3000 of the full 12K window. A run whose window is shorter resets as often per window,
  // at a whole number of 500-iteration densification steps (never less than one).
  TrainConfig c;
  c.iterations = 30000;
  EXPECT_EQ(c.densify_until(), 12000);
  EXPECT_EQ(c.opacity_reset_every(), 3000);
  c.iterations = 8000;  // window 6000: half the full one
  EXPECT_EQ(c.densify_until(), 6000);
  EXPECT_EQ(c.opacity_reset_every(), 1500);
  c.iterations = 2000;  // window 1500: 375 rounds to one densification step
  EXPECT_EQ(c.densify_until(), 1500);
  EXPECT_EQ(c.opacity_reset_every(), 500);
  c.iterations = 500;
  EXPECT_EQ(c.opacity_reset_every(), 500);
  c.iterations = 2000;
  c.densify.opacity_reset_interval = 12000;  // scaled: 1500, i.e. three steps
  EXPECT_EQ(c.opacity_reset_every(), 1500);
}

TEST(TrainConfig, ColourRateRisesInShortRuns) {
  // 3DGS's rate from the full schedule on; a shorter run x (30000 / iterations)^power; power 0 = fixed.
  TrainConfig c;
  c.iterations = 30000;
  EXPECT_FLOAT_EQ(c.sh_dc_rate(), c.lr.sh_dc);
  c.iterations = 60000;
  EXPECT_FLOAT_EQ(c.sh_dc_rate(), c.lr.sh_dc);
  c.iterations = 2000;  // the default power 0.5: x sqrt(15)
  EXPECT_NEAR(c.sh_dc_rate(), 2.5e-3 * std::sqrt(15.0), 1e-7);
  c.iterations = 500;  // shorter runs keep 2K's factor
  EXPECT_NEAR(c.sh_dc_rate(), 2.5e-3 * std::sqrt(15.0), 1e-7);
  c.iterations = 8000;
  EXPECT_NEAR(c.sh_dc_rate(), 2.5e-3 * std::sqrt(30000.0 / 8000.0), 1e-7);
  c.iterations = 7500;
  c.lr.sh_dc_short_run_power = 1.0f;
  EXPECT_NEAR(c.sh_dc_rate(), 1e-2, 1e-7);
  c.lr.sh_dc_short_run_power = 0.0f;
  EXPECT_FLOAT_EQ(c.sh_dc_rate(), c.lr.sh_dc);
  c.lr.sh_dc_short_run_power = 1.5f;
  EXPECT_THROW(c.validate("test"), Error);
  c.lr.sh_dc_short_run_power = -0.5f;
  EXPECT_THROW(c.validate("test"), Error);
}

TEST(TrainConfig, MirrorWorldPruneSchedule) {
  // A 4K intrinsic run shades from 2000: the prune runs there, and with _repeat after each later
  // densification, never in radiance mode or with the tolerance at 0.
  TrainConfig c;
  c.iterations = 4000;
  c.mode = TrainMode::Intrinsic;
  const int from = c.shading_from();
  ASSERT_EQ(from, 2000);
  EXPECT_TRUE(c.prunes_mirror_world_after(from, false)) << "on by default";
  EXPECT_TRUE(c.intrinsic.prune_mirror_world_repeat);
  c.intrinsic.prune_mirror_world = 0;
  EXPECT_FALSE(c.prunes_mirror_world_after(from, false)) << "0 = off";
  c.intrinsic.prune_mirror_world = 0.05f;
  c.intrinsic.prune_mirror_world_repeat = false;
  EXPECT_TRUE(c.prunes_mirror_world_after(from, false));
  EXPECT_TRUE(c.prunes_mirror_world_after(from, true));
  EXPECT_FALSE(c.prunes_mirror_world_after(from - 1, false));
  EXPECT_FALSE(c.prunes_mirror_world_after(from + 500, true)) << "once only without _repeat";
  c.intrinsic.prune_mirror_world_repeat = true;
  EXPECT_TRUE(c.prunes_mirror_world_after(from + 500, true));
  EXPECT_FALSE(c.prunes_mirror_world_after(from + 501, false)) << "only after a densification";
  EXPECT_FALSE(c.prunes_mirror_world_after(from - 500, true)) << "not during the warm-up";
  c.mode = TrainMode::Radiance;
  EXPECT_FALSE(c.prunes_mirror_world_after(from, false));
  EXPECT_FALSE(c.prunes_mirror_world_after(from + 500, true));
}
