// --mode auto's decision (train/setup/auto_mode.h): the glossy-mask fraction rule, when the detection
// runs, the mask folders, and the switch of a running trainer on the embedded default scene (masks hidden)
// with resume. The detection itself is tested in test_glossy_detection.cpp.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/image.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_folder.h"
#include "train/setup/auto_mode.h"
#include "train/setup/run_renderer.h"
#include "train/setup/training_setup.h"

namespace goris {
namespace {

namespace fs = std::filesystem;

// --- the mask-fraction rule --------------------------------------------------------------------------

std::vector<TrainView> views_with_masks(int n_views, int glossy_pixels_per_view, bool masks = true) {
  std::vector<TrainView> out;
  for (int i = 0; i < n_views; ++i) {
    TrainView v;
    v.name = "v" + std::to_string(i);
    v.camera.width = v.camera.height = 10;
    v.camera.fx = v.camera.fy = 11.0f;
    v.camera.cx = v.camera.cy = 5.0f;
    v.image.assign(300, 0.5f);
    if (masks) {
      v.glossy_mask.assign(100, 0.0f);
      for (int p = 0; p < glossy_pixels_per_view; ++p) v.glossy_mask[size_t(p)] = 0.8f;
    }
    out.push_back(std::move(v));
  }
  return out;
}

TEST(AutoMode, MaskFractionRule) {
  TrainConfig c;
  c.mode = TrainMode::Auto;
  EXPECT_NE(resolve_auto_mode(c, views_with_masks(4, 0)).find("empty"), std::string::npos);
  EXPECT_EQ(c.mode, TrainMode::Radiance);
  EXPECT_FALSE(c.input.auto_detect_glossy);

  c.mode = TrainMode::Auto;  // 1 % of the pixels: above the 0.5 % default
  EXPECT_NE(resolve_auto_mode(c, views_with_masks(4, 1)).find("mark"), std::string::npos);
  EXPECT_EQ(c.mode, TrainMode::Intrinsic);

  c.mode = TrainMode::Auto;
  c.intrinsic.auto_mask_fraction = 0.02f;
  resolve_auto_mode(c, views_with_masks(4, 1));
  EXPECT_EQ(c.mode, TrainMode::Radiance);
  EXPECT_DOUBLE_EQ(*glossy_mask_fraction(views_with_masks(4, 1)), 0.01);

  c.mode = TrainMode::Auto;
  c.iterations = 30000;
  const std::string long_run = resolve_auto_mode(c, views_with_masks(4, 0, false));
  EXPECT_NE(long_run.find("no glossy masks"), std::string::npos);
  EXPECT_EQ(long_run.find("caution"), std::string::npos);
  EXPECT_EQ(c.mode, TrainMode::Radiance);
  EXPECT_TRUE(c.input.auto_detect_glossy);
  c.mode = TrainMode::Auto;  // a run that ends before the geometry has settled decides anyway, with a caution
  c.iterations = 500;
  EXPECT_NE(resolve_auto_mode(c, views_with_masks(4, 0, false)).find("caution"), std::string::npos);
  EXPECT_FALSE(glossy_mask_fraction(views_with_masks(2, 0, false)).has_value());

  TrainConfig given;
  given.mode = TrainMode::Intrinsic;
  EXPECT_EQ(resolve_auto_mode(given, views_with_masks(2, 0)), "");
  EXPECT_EQ(given.mode, TrainMode::Intrinsic);
}

TEST(AutoMode, DetectionWaitsForTheGeometry) {
  TrainConfig c;
  c.intrinsic.detect_settled = 0;  // the planned start alone (the settled floor: the next test)
  c.iterations = 30000;
  EXPECT_EQ(auto_detection_iteration(c), 4000);  // the warm-up
  c.iterations = 4000;  // warm-up 533, but the geometry needs longer: half the run (2000, where the
                        // opacities are reset: just before)
  EXPECT_EQ(auto_detection_iteration(c), 1999);
  c.intrinsic.detect_after = 0;
  EXPECT_EQ(auto_detection_iteration(c), 1999);  // the warm-up keeps half of a short run too
  c.intrinsic.warmup_min_fraction = 0;
  EXPECT_EQ(auto_detection_iteration(c), 533);
  c.intrinsic.detect_after = 4000;
  c.intrinsic.warmup = 20000;  // a longer warm-up wins
  EXPECT_EQ(auto_detection_iteration(c), 2667);
}

TEST(AutoMode, DetectionNeverSeesAModelWhoseOpacitiesWereJustReset) {
  TrainConfig c;
  for (int n : {6000, 6500, 10000}) {  // their scaled opacity resets fall on iteration 4000
    c.iterations = n;
    ASSERT_EQ(4000 % c.opacity_reset_every(), 0) << n;
    EXPECT_EQ(auto_detection_iteration(c), 3999) << n;
  }
  // 5000: no reset at 4000 (past its densification window); 8000, 12000, 30000: the last reset before 4000
  // is at 3000, 2500 and 3000.
  for (int n : {5000, 8000, 12000, 30000}) {
    c.iterations = n;
    EXPECT_EQ(auto_detection_iteration(c), 4000) << n;
  }
}

TEST(AutoMode, ShortRunsDecideOnceTheGeometryHasSettledAndKeepTheirShadingPhase) {
  TrainConfig c;
  c.intrinsic.detect_settled = 2000;
  c.iterations = 2000;  // planned: half the run; the geometry settles only at 2000, the run's end
  EXPECT_EQ(planned_shading_start(c), 1000);
  EXPECT_EQ(auto_detection_iteration(c), 2000);
  TrainConfig l = lengthened_for_late_decision(c, 2000);
  EXPECT_EQ(l.iterations, 3000);  // the planned 1000 shading iterations follow the decision
  c.iterations = 3000;
  EXPECT_EQ(auto_detection_iteration(c), 2000);
  EXPECT_EQ(lengthened_for_late_decision(c, 2000).iterations, 3500);
  c.iterations = 500;  // too short to settle: decided at the end
  EXPECT_EQ(auto_detection_iteration(c), 500);
  EXPECT_EQ(lengthened_for_late_decision(c, 500).iterations, 750);
  c.iterations = 4000;  // long enough: as planned (just before the opacity reset at 2000), nothing lengthened
  EXPECT_EQ(auto_detection_iteration(c), 1999);
  const TrainConfig same = lengthened_for_late_decision(c, 2000);
  EXPECT_EQ(same.iterations, 4000);
  c.intrinsic.detect_settled = TrainConfig().intrinsic.detect_settled;  // the default, 4000: a 4K run
  EXPECT_EQ(auto_detection_iteration(c), 4000);                         // decides at its end ...
  EXPECT_EQ(lengthened_for_late_decision(c, 4000).iterations, 6000);   // ... and adds its 2K of shading
  c.iterations = 30000;  // the full schedule: at the warm-up's end, as planned
  EXPECT_EQ(auto_detection_iteration(c), 4000);
  c.iterations = 4000;
  c.iterations = 2000;
  c.intrinsic.detect_settled = 0;  // off: the planned start (1000, an opacity reset: just before)
  EXPECT_EQ(auto_detection_iteration(c), 999);
}

TEST(AutoMode, MaskFolderErrorsNameTheFile) {
  const fs::path dir = test::scratch_dir("auto_mode_mask_folder");
  std::vector<TrainView> views = views_with_masks(1, 0, false);
  try {
    load_glossy_mask_folder(dir, views);
    FAIL() << "a missing mask was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gloss_v0.png"), std::string::npos) << e.what();
  }
  save_png(dir / "gloss_v0.png", Image(12, 10, 1));
  EXPECT_THROW(load_glossy_mask_folder(dir, views), Error);
  Image ok(10, 10, 1);
  ok.pixels.fill_zero();
  ok.pixels[3] = 1.0f;
  save_png(dir / "gloss_v0.png", ok);
  load_glossy_mask_folder(dir, views);
  EXPECT_FLOAT_EQ(views[0].glossy_mask[3], 1.0f);
  EXPECT_THROW(load_glossy_mask_folder(dir / "absent", views), Error);
}

// --- the switch on the default scene ----------------------------------------------------------------

// A tiny auto run on the default scene with its glossy masks hidden: 32 px, 40 iterations, detection
// after 20 (the warm-up set to 15000 of 30000, scaled).
TrainConfig tiny_auto_config() {
  TrainConfig c;
  c.mode = TrainMode::Auto;
  c.input.data = (test::resource_dir() / "default_scene").string();
  c.device = DeviceChoice::CPU;
  c.input.resolution = 32;
  c.iterations = 40;
  c.init.random_points = 4000;
  c.input.use_glossy_masks = false;
  c.intrinsic.warmup = 15000;
  c.intrinsic.env_resolution = 8;
  c.intrinsic.net_hidden_layers = 1;
  c.intrinsic.detect_settled = 0;  // decide at the planned shading start (the late decision has its own test)
  c.bookkeeping.checkpoint_interval = 10;
  c.bookkeeping.keep_checkpoints = 10;
  return c;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

TEST(AutoMode, SwitchesToIntrinsicWithTheDetectedMasksAndResumes) {
  const fs::path run = test::scratch_dir("auto_mode_switch");
  TrainConfig c = tiny_auto_config();
  c.intrinsic.detect_threshold = 0.0f;  // every scored pixel: the decision is forced to "glossy"
  c.intrinsic.detect_fraction = 0.0f;
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  EXPECT_EQ(p.config.mode, TrainMode::Radiance);
  EXPECT_TRUE(p.config.input.auto_detect_glossy);
  EXPECT_NE(p.auto_mode_reason.find("no glossy masks"), std::string::npos);
  EXPECT_EQ(auto_detection_iteration(p.config), 20);
  for (const TrainView& v : t.views()) EXPECT_TRUE(v.glossy_mask.empty());

  // Step by hand up to the end of the warm-up: nothing happens before it.
  while (t.state().iteration < 20) {
    EXPECT_FALSE(apply_auto_mode(t, run).has_value());
    t.step();
    if (t.state().iteration == 10) t.save_checkpoint(checkpoint_path(run, 10));
  }
  EXPECT_FALSE(t.intrinsic());
  const std::array<int, kGroupCount> steps_before = t.state().adam.steps;
  EXPECT_EQ(steps_before[size_t(ParamGroup::Region)], 0);
  const float init_region = std::log(0.9f / 0.1f);  // the material extras never trained in radiance mode
  EXPECT_NEAR(t.model().values(Param::ExtraLogit)[extra::kRegion], init_region, 1e-5f);

  const std::optional<AutoDecision> d = apply_auto_mode(t, run);
  ASSERT_TRUE(d.has_value());
  EXPECT_TRUE(d->glossy) << d->message();
  EXPECT_GT(d->covered, 0u);
  EXPECT_EQ(d->iteration, 20);
  EXPECT_TRUE(t.intrinsic());
  EXPECT_NE(as_intrinsic(t.renderer().get()), nullptr);
  EXPECT_FALSE(t.config().input.auto_detect_glossy);
  EXPECT_EQ(fs::path(t.config().input.glossy_mask_dir), run / "detected_gloss");
  EXPECT_EQ(t.config().shading_from(), 20) << "shading starts at the switch";
  EXPECT_FALSE(apply_auto_mode(t, run).has_value()) << "decided twice";
  // Masks: files at the training size, the views' glossy masks, the summary, config.json.
  for (const TrainView& v : t.views()) {
    ASSERT_EQ(v.glossy_mask.size(), size_t(v.camera.width) * v.camera.height);
    const Image m = load_mask(run / "detected_gloss" / ("gloss_" + v.name + ".png"));
    ASSERT_EQ(m.pixel_count(), v.glossy_mask.size());
    for (size_t q = 0; q < m.pixel_count(); ++q) ASSERT_EQ(m.pixels[q], v.glossy_mask[q]);
  }
  const nlohmann::json summary = read_json(run / "detected_gloss" / "summary.json");
  EXPECT_EQ(summary["decision"], "intrinsic");
  EXPECT_EQ(summary["iteration"], 20);
  EXPECT_TRUE(summary.contains("seconds") && summary.contains("fraction") && summary.contains("threshold"));
  EXPECT_EQ(read_run_config(run).mode, TrainMode::Intrinsic);
  // The extras' groups start fresh; the others keep their step counts.
  for (ParamGroup g : {ParamGroup::Materials, ParamGroup::Region, ParamGroup::Label})
    EXPECT_EQ(t.state().adam.steps[size_t(g)], 0) << group_name(g);
  const std::vector<float> m = t.model().tensor(Param::ExtraLogit).adam_m.to_host();
  for (float x : m) ASSERT_EQ(x, 0.0f);

  t.step();
  EXPECT_EQ(t.state().adam.steps[size_t(ParamGroup::Region)], 1);
  EXPECT_EQ(t.state().adam.steps[size_t(ParamGroup::Position)], steps_before[size_t(ParamGroup::Position)] + 1);

  // Through run(): the checkpoints after the switch carry the intrinsic configuration.
  Trainer::RunOptions ro;
  ro.run_dir = run;
  ro.before_step = [&](Trainer& tr) { apply_auto_mode(tr, run); };
  t.run(ro);
  write_trained_run(run, t, *t.renderer());
  EXPECT_TRUE(fs::exists(run / "environment.png"));
  const std::vector<std::uint8_t> mask0(t.views()[0].glossy_mask.begin(), t.views()[0].glossy_mask.end());

  // Resumed with more iterations: intrinsic again, with the same masks.
  std::optional<ResumePoint> r = read_latest_checkpoint(run);
  ASSERT_TRUE(r.has_value());
  TrainConfig rc = r->checkpoint.config;
  EXPECT_EQ(rc.mode, TrainMode::Intrinsic);
  rc.iterations = 45;
  PreparedTraining p2 = prepare_training(run, rc, std::move(r));
  EXPECT_TRUE(p2.trainer->intrinsic());
  EXPECT_EQ(p2.auto_mode_reason, "");
  EXPECT_EQ(p2.glossy_views, p2.trainer->views().size());
  const std::vector<float>& g0 = p2.trainer->views()[0].glossy_mask;
  ASSERT_EQ(g0.size(), mask0.size());
  for (size_t q = 0; q < g0.size(); ++q) ASSERT_EQ(g0[q], float(mask0[q]));
  p2.trainer->step();

  // A checkpoint written before the decision resumes in radiance mode with the detection still to come.
  const Checkpoint early = read_checkpoint(checkpoint_path(run, 10), Device::CPU);
  EXPECT_EQ(early.config.mode, TrainMode::Radiance);
  EXPECT_TRUE(early.config.input.auto_detect_glossy);
}

TEST(AutoMode, StaysRadianceWhenNothingIsGlossy) {
  const fs::path run = test::scratch_dir("auto_mode_radiance");
  TrainConfig c = tiny_auto_config();
  c.iterations = 24;
  c.intrinsic.warmup = 25000;  // detection after 20
  c.intrinsic.detect_threshold = 1e6f;  // nothing is glossy
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  const auto renderer_before = t.renderer();
  std::vector<AutoDecision> decisions;
  Trainer::RunOptions ro;
  ro.run_dir = run;
  ro.before_step = [&](Trainer& tr) {
    if (auto d = apply_auto_mode(tr, run)) decisions.push_back(*d);
  };
  t.run(ro);
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_FALSE(decisions[0].glossy);
  EXPECT_EQ(decisions[0].detected, 0u);
  EXPECT_NE(decisions[0].message().find("radiance to the end"), std::string::npos);
  EXPECT_FALSE(t.intrinsic());
  EXPECT_EQ(t.renderer(), renderer_before);
  EXPECT_FALSE(t.config().input.auto_detect_glossy);
  EXPECT_TRUE(t.config().input.glossy_mask_dir.empty());
  for (ParamGroup g : {ParamGroup::Materials, ParamGroup::Region, ParamGroup::Label})
    EXPECT_EQ(t.state().adam.steps[size_t(g)], 0) << group_name(g);
  write_trained_run(run, t, *t.renderer());
  EXPECT_FALSE(fs::exists(run / "environment.png"));
  EXPECT_EQ(read_json(run / "detected_gloss" / "summary.json")["decision"], "radiance");
  const TrainConfig saved = read_run_config(run);
  EXPECT_EQ(saved.mode, TrainMode::Radiance);
  EXPECT_FALSE(saved.input.auto_detect_glossy);
  const Checkpoint last = read_checkpoint(checkpoint_path(run, 24), Device::CPU);
  EXPECT_FALSE(last.config.input.auto_detect_glossy);
}

TEST(AutoMode, ALateGlossyDecisionAtTheEndLengthensTheRun) {
  // 40 iterations, shading planned from 20, but the geometry "settles" only at 40: run() decides after
  // the last iteration and goes on for the planned 20 shading iterations.
  const fs::path run = test::scratch_dir("auto_mode_late");
  TrainConfig c = tiny_auto_config();
  c.intrinsic.detect_settled = 40;
  c.intrinsic.detect_threshold = 0.0f;  // forced "glossy"
  c.intrinsic.detect_fraction = 0.0f;
  c.bookkeeping.checkpoint_interval = 100;
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  EXPECT_EQ(auto_detection_iteration(p.config), 40);
  std::vector<AutoDecision> decisions;
  Trainer::RunOptions ro;
  ro.run_dir = run;
  ro.before_step = [&](Trainer& tr) {
    if (auto d = apply_auto_mode(tr, run)) decisions.push_back(*d);
  };
  EXPECT_EQ(t.run(ro), Trainer::RunResult::Finished);
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_TRUE(decisions[0].glossy);
  EXPECT_EQ(decisions[0].iteration, 40);
  EXPECT_EQ(decisions[0].extended_by, 20);
  EXPECT_NE(decisions[0].message().find("grows by 20 iterations"), std::string::npos) << decisions[0].message();
  EXPECT_TRUE(t.intrinsic());
  EXPECT_EQ(t.state().iteration, 60);
  EXPECT_EQ(t.config().iterations, 60);
  EXPECT_EQ(t.config().shading_from(), 40);
  EXPECT_GT(t.state().adam.steps[size_t(ParamGroup::Region)], 0);
  const TrainConfig saved = read_run_config(run);
  EXPECT_EQ(saved.iterations, 60);
  EXPECT_EQ(saved.mode, TrainMode::Intrinsic);

  // The same run on a scene with nothing glossy keeps its length.
  const fs::path run2 = test::scratch_dir("auto_mode_late_radiance");
  c.intrinsic.detect_threshold = 1e6f;
  c.intrinsic.detect_fraction = 0.0008f;
  PreparedTraining p2 = prepare_training(run2, c, std::nullopt);
  decisions.clear();
  ro.run_dir = run2;
  ro.before_step = [&](Trainer& tr) {
    if (auto d = apply_auto_mode(tr, run2)) decisions.push_back(*d);
  };
  p2.trainer->run(ro);
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_FALSE(decisions[0].glossy);
  EXPECT_EQ(decisions[0].extended_by, 0);
  EXPECT_EQ(p2.trainer->state().iteration, 40);
  EXPECT_FALSE(p2.trainer->intrinsic());
}

TEST(AutoMode, EmbeddedSceneMasksChooseIntrinsic) {
  TrainConfig c = tiny_auto_config();
  c.input.use_glossy_masks = true;
  c.iterations = 1;
  PreparedTraining p = prepare_training(test::scratch_dir("auto_mode_masks"), c, std::nullopt);
  EXPECT_EQ(p.config.mode, TrainMode::Intrinsic);
  EXPECT_FALSE(p.config.input.auto_detect_glossy);
  EXPECT_NE(p.auto_mode_reason.find("mark"), std::string::npos) << p.auto_mode_reason;
}

}  // namespace
}  // namespace goris
