// The adaptive Gaussian budget (densify_stop=adaptive, core/train/densify_stop.h): the stop rule on
// synthetic held-out PSNR histories, the check schedule, held-out views left out of the sampler while
// densification runs and back afterwards, prune-only after the stop, bit-exact resume across the decision
// on the embedded default scene, and older checkpoints still loading.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/io/dataset.h"
#include "core/train/checkpoint.h"
#include "core/train/densify_stop.h"
#include "core/train/held_out_views.h"
#include "core/train/train_setup.h"
#include "core/train/trainer.h"
#include "core/util/error.h"
#include "render/train/raster_renderer.h"
#include "tests/support/test_support.h"
#include "core/util/fnv1a.h"

using namespace goris;

namespace {

std::vector<HeldOutCheck> history(const std::vector<double>& psnr, int first = 100, int step = 100) {
  std::vector<HeldOutCheck> h;
  for (size_t i = 0; i < psnr.size(); ++i) h.push_back({first + int(i) * step, psnr[i], 1000});
  return h;
}

DensifyStopPlan plan_2k() {
  TrainConfig c;
  c.iterations = 2000;
  c.densify.stop = "adaptive";
  c.densify.stop_min_steps = 1;  // the default 2 leaves a 2K run fixed (tested below)
  return densify_stop_plan(c, /*densify_until=*/1000, /*intrinsic=*/false);
}

}  // namespace

TEST(DensifyStopRule, GainIsTheLastWindowOverTheBestBefore) {
  EXPECT_FALSE(held_out_gain(history({20, 21}), 0, 2).has_value()) << "needs window + 1 checks";
  EXPECT_NEAR(*held_out_gain(history({20, 21, 21.5}), 0, 2), 1.5, 1e-12);
  EXPECT_NEAR(*held_out_gain(history({20, 21, 21.5, 21.55, 21.58}), 0, 2), 0.08, 1e-9);
  // One noisy check does not stop a rising curve: the window's best counts.
  EXPECT_NEAR(*held_out_gain(history({20, 21, 20.5, 21.8}), 0, 2), 0.8, 1e-9);
  // A drop gives a negative gain.
  EXPECT_LT(*held_out_gain(history({20, 22, 21.5, 21.7}), 0, 2), 0);
  // Window 1: the last check against all before it.
  EXPECT_NEAR(*held_out_gain(history({20, 21, 21.05}), 0, 1), 0.05, 1e-9);
  // Only checks after `since` count: iterations 100..500, since 300 leaves 400 and 500.
  EXPECT_FALSE(held_out_gain(history({20, 21, 22, 10, 11}), 300, 2).has_value());
  EXPECT_NEAR(*held_out_gain(history({20, 21, 22, 10, 11, 11.5}), 300, 2), 1.5, 1e-9);
}

TEST(DensifyStopRule, RecordStopsOnAPlateauAndSaysSo) {
  DensifyStopPlan p = plan_2k();
  DensifyStopState s;
  const std::vector<double> curve = {18, 19, 19.6, 19.9, 19.95, 19.97, 19.98};
  std::string note;
  size_t i = 0;
  for (; i < curve.size() && !s.stopped(); ++i) note = record_held_out_check(s, p, 500 + int(i) * 33, curve[i], 1000 + i);
  // Check 5 (19.95): max(19.9, 19.95) - 19.6 = 0.35; check 6 (19.97): max(19.95, 19.97) - 19.9 = 0.07 < 0.1.
  EXPECT_EQ(i, 6u);
  EXPECT_EQ(s.stopped_at, 500 + 5 * 33);
  EXPECT_NE(note.find("stopped at iteration 665 with 1005 Gaussians"), std::string::npos) << note;
  const nlohmann::json j = densify_stop_json(s, p, {"r_000", "r_008"});
  EXPECT_EQ(j["stopped_at"], 665);
  EXPECT_EQ(j["gaussians_at_stop"], 1005);
  EXPECT_EQ(j["checks"].size(), 6u);
  EXPECT_EQ(j["held_out_views"][1], "r_008");

  // A curve that keeps rising reaches the end of the window without a stop, and says so there.
  DensifyStopState r;
  for (int it = 500; it <= 1000; ++it)
    if (p.checks_at(it, r)) note = record_held_out_check(r, p, it, 15 + 0.01 * it, 1000);
  EXPECT_FALSE(r.stopped());
  EXPECT_NE(note.find("no stop before the end of the window"), std::string::npos) << note;
}

TEST(DensifyStopRule, ChecksFollowTheScaledScheduleAndSkipResets) {
  const DensifyStopPlan p = plan_2k();
  EXPECT_EQ(p.check_interval, 33);  // 500 of 30K scaled to 2K
  DensifyStopState s;
  std::vector<int> checks;
  for (int it = 1; it <= 2000; ++it)
    if (p.checks_at(it, s)) checks.push_back(it);
  ASSERT_FALSE(checks.empty());
  EXPECT_EQ(checks.front(), 500);
  EXPECT_EQ(checks[1], 533);
  EXPECT_EQ(checks.back(), 1000) << "the densification step at the window's end is checked";
  EXPECT_EQ(checks.size(), 17u);  // 500 + 33k for k = 0..15, and 1000
  EXPECT_TRUE(p.holds_out(1, s));
  EXPECT_TRUE(p.holds_out(1000, s));
  EXPECT_FALSE(p.holds_out(1001, s));
  s.stopped_at = 700;
  EXPECT_FALSE(p.holds_out(701, s));
  EXPECT_FALSE(p.checks_at(731, s));

  // 30K schedule: opacity resets at 3000, 6000, 9000 (12000 is the window's end: no step follows it), and
  // the intrinsic warm-up ends at 4000.
  TrainConfig c;
  c.densify.stop = "adaptive";
  const DensifyStopPlan full = densify_stop_plan(c, 12000, /*intrinsic=*/true);
  EXPECT_EQ(full.check_interval, 500);
  EXPECT_EQ(full.incomparable_before(2500), 0);
  EXPECT_EQ(full.incomparable_before(3000), 0) << "the check at a reset's iteration comes before the reset";
  EXPECT_EQ(full.incomparable_before(3500), 3000);
  EXPECT_EQ(full.incomparable_before(4500), 4000);
  EXPECT_EQ(full.incomparable_before(9500), 9000);
  EXPECT_EQ(densify_stop_plan(c, 12000, false).incomparable_before(4500), 3000);
  // After a reset the PSNR collapses; the rule must not read that as "no more improvement".
  DensifyStopState r;
  for (int it = 500; it <= 3000; it += 500) record_held_out_check(r, full, it, 20 + it / 1000.0, 1000);
  EXPECT_FALSE(r.stopped());
  EXPECT_EQ(record_held_out_check(r, full, 3500, 12, 1000), "");
  EXPECT_EQ(record_held_out_check(r, full, 4000, 18, 1000), "");
  EXPECT_FALSE(r.stopped()) << "3500 and 4000 are compared with nothing before the reset";
  // Fixed (the default) never holds out or checks.
  TrainConfig f;
  const DensifyStopPlan fixed = densify_stop_plan(f, 12000, false);
  EXPECT_FALSE(fixed.holds_out(10, s) || fixed.checks_at(500, DensifyStopState{}));
}

TEST(DensifyStopRule, ActsOnlyWithEnoughStepsToSkip) {
  TrainConfig c;
  c.densify.stop = "adaptive";
  c.iterations = 2000;  // checks 500, 533, 566 -> the first stop at 566; only the step at 1000 after it
  const DensifyStopPlan p2 = densify_stop_plan(c, 1000, true);
  EXPECT_EQ(p2.earliest_stop, 566);
  EXPECT_EQ(p2.skippable_steps, 1);
  EXPECT_FALSE(p2.active());
  EXPECT_FALSE(p2.holds_out(1, DensifyStopState{}) || p2.checks_at(566, DensifyStopState{}));
  EXPECT_NE(p2.inactive_reason().find("1 densification step(s) after the earliest possible stop (iteration 566)"),
            std::string::npos) << p2.inactive_reason();
  c.iterations = 6000;  // checks every 100: first stop at 700, steps 1000 .. 3000
  const DensifyStopPlan p6 = densify_stop_plan(c, 3000, false);
  EXPECT_EQ(p6.earliest_stop, 700);
  EXPECT_EQ(p6.skippable_steps, 5);
  EXPECT_TRUE(p6.active());
  EXPECT_EQ(p6.inactive_reason(), "");
  c.iterations = 30000;
  EXPECT_EQ(densify_stop_plan(c, 12000, false).skippable_steps, 22);  // 1500 .. 12000 (checks 500, 1000, 1500)
  // No densification at all (a stage-2 fine-tune under a copied configuration): nothing to say.
  EXPECT_EQ(densify_stop_plan(c, 0, false).inactive_reason(), "");
  EXPECT_FALSE(densify_stop_plan(c, 0, false).active());
}

TEST(HeldOutViews, EveryNthAtLeastOneNeverAll) {
  EXPECT_EQ(held_out_view_indices(20, 8), (std::vector<std::uint32_t>{0, 8, 16}));
  EXPECT_EQ(held_out_view_indices(3, 8), (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(held_out_view_indices(2, 2), (std::vector<std::uint32_t>{0}));
  EXPECT_THROW(held_out_view_indices(1, 8), Error);
  EXPECT_THROW(held_out_view_indices(10, 1), Error);
  EXPECT_EQ(epoch_views(5, {0, 3}), (std::vector<std::uint32_t>{1, 2, 4}));
  EXPECT_EQ(epoch_views(3, {}), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(DensifyStopConfig, KeysRoundTripAndBadValuesAreRejected) {
  TrainConfig c;
  EXPECT_EQ(c.densify.stop, "fixed");
  c.densify.stop = "adaptive";
  c.densify.holdout_every = 5;
  c.densify.stop_check_interval = 250;
  c.densify.stop_window = 3;
  c.densify.stop_min_gain = 0.05f;
  TrainConfig back;
  from_json(nlohmann::json(c), back);
  EXPECT_EQ(back.densify.stop, "adaptive");
  EXPECT_EQ(back.densify.holdout_every, 5);
  EXPECT_EQ(back.densify.stop_check_interval, 250);
  EXPECT_EQ(back.densify.stop_window, 3);
  EXPECT_FLOAT_EQ(back.densify.stop_min_gain, 0.05f);
  auto invalid = [](auto edit) {
    TrainConfig t;
    edit(t);
    try {
      t.validate("cfg");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(invalid([](TrainConfig& t) { t.densify.stop = "sometimes"; }).find("densify_stop"), std::string::npos);
  EXPECT_NE(invalid([](TrainConfig& t) { t.densify.holdout_every = 1; }).find("densify_holdout_every"), std::string::npos);
  EXPECT_NE(invalid([](TrainConfig& t) { t.densify.stop_window = 0; }).find("densify_stop_window"), std::string::npos);
  EXPECT_NE(invalid([](TrainConfig& t) { t.densify.stop_min_gain = NAN; }).find("densify_stop_min_gain"), std::string::npos);
}

TEST(DensifyStop, PruneOnlyAddsNoGaussians) {
  GaussianModel m(Device::CPU);
  m.allocate(4);
  for (int i = 0; i < 4; ++i) {
    for (int a = 0; a < 3; ++a) {
      m.values(Param::Position)[i * 3 + a] = float(i);
      m.values(Param::LogScale)[i * 3 + a] = std::log(i < 2 ? 0.001f : 0.5f);  // two clone-sized, two split-sized
    }
    m.values(Param::Rotation)[i * 4] = 1;
    m.values(Param::OpacityLogit)[i] = i == 3 ? -6.0f : 2.0f;  // the last one is transparent
  }
  DensifyStats st;
  st.reset(4, Device::CPU);
  for (int i = 0; i < 4; ++i) st.grad_accum[i] = st.denom[i] = 1;  // far above any threshold
  DensifySettings ds;
  GaussianModel grown = m.copy_to(Device::CPU);
  const DensifyCounts g = densify_and_prune(grown, st, ds, 1.0f, false, 1);
  EXPECT_GT(g.cloned + g.split, 0u);
  const DensifyCounts p = densify_and_prune(m, st, ds, 1.0f, false, 1, /*grow=*/false);
  EXPECT_EQ(p.cloned + p.split, 0u);
  EXPECT_EQ(p.pruned, 1u);
  EXPECT_EQ(m.count(), 3u);
}

namespace {

// The embedded default scene at 32 px with a few thousand random points, and a tiny schedule in which
// densification runs from 50 to 200 with held-out checks every 15 iterations.
struct TinyRun {
  TrainConfig config;
  Dataset dataset;
  std::vector<TrainView> views;
  float extent = 1;
  std::shared_ptr<RasterRenderer> renderer;

  explicit TinyRun(float min_gain, int iterations = 300) {
    config.iterations = iterations;
    config.device = "cpu";
    config.resolution = 32;
    config.random_init_points = 1500;
    config.random_init_box_ratio = 0.15f;
    config.data = (test::resource_dir() / "default_scene").string();
    config.densify.from_iter = 50;
    config.densify.interval = 50;
    config.densify.until_iter = 200;
    config.densify_until_fraction = 1;
    config.densify.opacity_reset_interval = 1 << 30;
    config.densify.stop = "adaptive";
    config.densify.stop_check_interval = 15 * 30000 / iterations;
    config.densify.stop_min_gain = min_gain;
    config.densify.grad_threshold = 5e-5f;
    config.densify.stop_min_steps = 1;  // a tiny schedule has few steps to skip; the guard has its own test
    config.depth_normal_weight = 0;
    config.checkpoint_interval = 0;
    const DatasetOptions o = dataset_options(config);
    dataset = load_dataset(config.data, o);
    views = load_train_views(dataset.train, o);
    extent = scene_extent(dataset);
    renderer = std::make_shared<RasterRenderer>(RasterRenderer::settings_for(config), Device::CPU);
  }
  Trainer trainer() const {
    return Trainer(config, views, extent, renderer, Trainer::initial_state(config, initial_model(dataset, config, Device::CPU)));
  }
};

std::vector<float> all_values(const GaussianModel& m) {
  std::vector<float> out;
  for (int p = 0; p < kParamCount; ++p)
    for (const Buffer<float>* b : {&m.tensor(Param(p)).value, &m.tensor(Param(p)).adam_m, &m.tensor(Param(p)).adam_v}) {
      const auto h = b->to_host();
      out.insert(out.end(), h.begin(), h.end());
    }
  return out;
}

}  // namespace

TEST(DensifyStop, HeldOutViewsLeaveTheSamplerWhileDensifyingAndComeBack) {
  for (const float min_gain : {1000.0f, -1000.0f}) {  // stops at the first decidable check / never stops
    TinyRun run(min_gain, min_gain > 0 ? 170 : 300);
    Trainer t = run.trainer();
    const std::vector<std::uint32_t> held = held_out_view_indices(run.views.size(), 8);
    ASSERT_EQ(held, (std::vector<std::uint32_t>{0, 8, 16, 24, 32}));  // 40 views
    int checks = 0, back_at = 0;
    while (!t.finished()) {
      const StepStats s = t.step();
      const int it = t.state().iteration;
      checks += s.held_out_check;
      const bool is_held = std::count(held.begin(), held.end(), std::uint32_t(s.view)) > 0;
      const int hold_until = t.state().densify_stop.stopped() ? t.state().densify_stop.stopped_at : 200;
      if (it <= hold_until) EXPECT_FALSE(is_held) << "iteration " << it << " trained on held-out view " << s.view;
      if (is_held && !back_at) back_at = it;
      if (s.densify.after > 0 && t.state().densify_stop.stopped())
        EXPECT_EQ(s.densify.cloned + s.densify.split, 0u) << "iteration " << it << ": prune only after the stop";
    }
    const DensifyStopState& st = t.state().densify_stop;
    if (min_gain > 0) {
      EXPECT_EQ(st.stopped_at, 80) << "checks at 50, 65, 80: the first with a gain to judge";
      EXPECT_EQ(checks, 3);
    } else {
      EXPECT_FALSE(st.stopped());
      EXPECT_EQ(checks, 13);  // 50, 65, ..., 200 and the densification steps 100 and 150
      EXPECT_EQ(st.checks.back().iteration, 200);
    }
    const int hold_until = st.stopped() ? st.stopped_at : 200;
    EXPECT_GT(back_at, hold_until) << "held-out views rejoin training";
    EXPECT_LE(back_at, hold_until + 75) << "within the rest of this epoch (35 views) and the next";
    for (const HeldOutCheck& c : st.checks) EXPECT_TRUE(std::isfinite(c.psnr) && c.psnr > 5) << c.psnr;
  }
}

TEST(DensifyStop, ResumeAcrossTheDecisionIsBitExact) {
  // Checkpoint at 70 holds checks 50 and 65; the resumed run must stop at 80 exactly as the straight one.
  TinyRun run(1000.0f, 100);
  Trainer straight = run.trainer();
  while (!straight.finished()) straight.step();
  ASSERT_EQ(straight.state().densify_stop.stopped_at, 80);

  Trainer first = run.trainer();
  while (first.state().iteration < 70) first.step();
  const auto dir = test::scratch_dir("densify_stop_resume");
  first.save_checkpoint(dir / "a.ckpt");
  Checkpoint ck = read_checkpoint(dir / "a.ckpt", Device::CPU);
  ASSERT_EQ(ck.state.densify_stop.checks.size(), 2u);
  EXPECT_EQ(ck.state.densify_stop.checks[1].psnr, first.state().densify_stop.checks[1].psnr);
  Trainer resumed(ck.config, run.views, run.extent, run.renderer, std::move(ck.state));
  while (!resumed.finished()) resumed.step();

  EXPECT_EQ(resumed.state().densify_stop.stopped_at, 80);
  ASSERT_EQ(resumed.model().count(), straight.model().count());
  EXPECT_EQ(all_values(resumed.model()), all_values(straight.model()));
  EXPECT_EQ(resumed.state().view_stack, straight.state().view_stack);
  ASSERT_EQ(resumed.state().densify_stop.checks.size(), straight.state().densify_stop.checks.size());
  for (size_t i = 0; i < straight.state().densify_stop.checks.size(); ++i)
    EXPECT_EQ(resumed.state().densify_stop.checks[i].psnr, straight.state().densify_stop.checks[i].psnr);
}

TEST(DensifyStop, RunWritesTheRecordAndTellsTheDecision) {
  TinyRun run(1000.0f, 110);
  Trainer t = run.trainer();
  const auto dir = test::scratch_dir("densify_stop_run");
  Trainer::RunOptions o;
  o.run_dir = dir;
  std::vector<std::string> notes;
  o.on_note = [&](const std::string& n) { notes.push_back(n); };
  ASSERT_EQ(t.run(o), Trainer::RunResult::Finished);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("stopped at iteration 80"), std::string::npos) << notes[0];
  std::ifstream in(dir / "densify_stop.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["densify_stop"], "adaptive");
  EXPECT_EQ(j["stopped_at"], 80);
  EXPECT_EQ(j["checks"].size(), 3u);
  EXPECT_EQ(j["checks"][2]["gaussians"], j["gaussians_at_stop"]);
  EXPECT_EQ(j["held_out_views"].size(), 5u);
  EXPECT_EQ(j["held_out_views"][0], run.views[0].name);
}

TEST(DensifyStop, TooShortAnAdaptiveRunTrainsExactlyAsAFixedOne) {
  TinyRun fixed_run(0.1f, 100), adaptive_run(0.1f, 100);
  fixed_run.config.densify.stop = "fixed";
  adaptive_run.config.densify.stop_min_steps = 2;  // first stop at 80, one step (100) after it
  Trainer f = fixed_run.trainer();
  while (!f.finished()) f.step();
  Trainer a = adaptive_run.trainer();
  const auto dir = test::scratch_dir("densify_stop_inactive");
  Trainer::RunOptions o;
  o.run_dir = dir;
  std::vector<std::string> notes;
  o.on_note = [&](const std::string& n) { notes.push_back(n); };
  ASSERT_EQ(a.run(o), Trainer::RunResult::Finished);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("adaptive densification inactive: 1 densification step(s)"), std::string::npos) << notes[0];
  EXPECT_TRUE(a.state().densify_stop.checks.empty());
  EXPECT_EQ(all_values(a.model()), all_values(f.model()));
  std::ifstream in(dir / "densify_stop.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["inactive_reason"].is_string());
  EXPECT_TRUE(j["held_out_views"].empty());
}

TEST(DensifyStop, VersionTwoCheckpointsStillLoad) {
  // A version-4 file with an empty record, turned into the version-3 layout (the emit-weight block, an 8-byte
  // count and its floats, dropped) and the version-2 layout (also the record: 8-byte count + 4-byte stop
  // iteration), the version field and the checksum rewritten each time.
  TinyRun run(-1000.0f, 20);
  Trainer t = run.trainer();
  for (int i = 0; i < 5; ++i) t.step();
  const auto dir = test::scratch_dir("densify_stop_v2");
  t.save_checkpoint(dir / "v4.ckpt");
  std::ifstream in(dir / "v4.ckpt", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t version;
  std::memcpy(&version, bytes.data() + 8, 4);
  ASSERT_EQ(version, 4u);
  const std::size_t emit_block = 8 + 4 * t.state().emit_weights.size();
  const auto older = [&](std::uint32_t v, std::size_t dropped, const char* name) {
    std::string old = bytes.substr(0, bytes.size() - 8 - dropped);
    std::memcpy(old.data() + 8, &v, 4);
    const std::uint64_t sum = fnv1a(old);
    old.append(reinterpret_cast<const char*>(&sum), 8);
    std::ofstream(dir / name, std::ios::binary) << old;
    return read_checkpoint(dir / name, Device::CPU);
  };
  for (const auto& [v, dropped, name] : {std::tuple{3u, emit_block, "v3.ckpt"}, std::tuple{2u, emit_block + 12, "v2.ckpt"}}) {
    SCOPED_TRACE(name);
    const Checkpoint ck = older(v, dropped, name);
    EXPECT_EQ(ck.state.iteration, 5);
    EXPECT_TRUE(ck.state.densify_stop.checks.empty());
    EXPECT_FALSE(ck.state.densify_stop.stopped());
    EXPECT_TRUE(ck.state.emit_weights.empty());
    EXPECT_EQ(all_values(ck.state.model), all_values(t.model()));
  }

  // A stop iteration past the checkpoint's own iteration is refused, naming the file.
  std::string bad = bytes.substr(0, bytes.size() - 8);
  const std::int32_t later = 999;
  std::memcpy(bad.data() + bad.size() - emit_block - 4, &later, 4);
  const std::uint64_t bad_sum = fnv1a(bad);
  bad.append(reinterpret_cast<const char*>(&bad_sum), 8);
  std::ofstream(dir / "bad.ckpt", std::ios::binary) << bad;
  try {
    read_checkpoint(dir / "bad.ckpt", Device::CPU);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.ckpt"), std::string::npos) << e.what();
  }
}

TEST(DensifyStop, AdaptiveNeedsTwoViews) {
  TinyRun run(0.1f, 100);
  std::vector<TrainView> one(run.views.begin(), run.views.begin() + 1);
  EXPECT_THROW(Trainer(run.config, one, run.extent, run.renderer,
                       Trainer::initial_state(run.config, initial_model(run.dataset, run.config, Device::CPU))),
               Error);
}
