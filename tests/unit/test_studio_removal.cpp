// Stage 2 in the editor: the progress tracker's per-step status, overall fraction and ETA (and that a
// cancelled step never reads as done), and the removal session on a tiny run of the embedded scene:
// errors end in the Error state, a cancel leaves a resumable folder, a full run completes every step.
#include <algorithm>
#include <chrono>

#include "core/scene/selection_points.h"
#include "core/util/error.h"
#include "removal/selection/selection_file.h"
#include "tests/support/test_support.h"
#include "train/run/run_folder.h"
#include "ui/document/removal_session.h"
#include "ui/document/trainer_session.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

TEST(StudioRemovalProgress, TracksStepsFractionAndEta) {
  RemovalCostModel cost;
  cost.weight = {1, 1, 1, 1, 1, 1, 4};  // fine-tune: 40 % of the work
  RemovalProgressTracker t(cost);
  EXPECT_EQ(t.current_step(), -1);
  EXPECT_EQ(t.fraction(), 0.0);
  EXPECT_LT(t.eta_s(1.0), 0.0);  // nothing known yet
  t.update({RemovalStep::Selection, 0, 1, ""}, 0.0);
  t.update({RemovalStep::Selection, 1, 1, "12 of 300 Gaussians"}, 1.0);
  EXPECT_TRUE(t.steps()[0].complete);
  EXPECT_EQ(t.steps()[0].detail, "12 of 300 Gaussians");
  t.update({RemovalStep::LightingMasks, 0, 1, ""}, 1.5);
  EXPECT_DOUBLE_EQ(t.steps()[0].seconds, 1.5);  // ends where the next step starts
  t.update({RemovalStep::LightingMasks, 5, 10, "r_005"}, 2.0);
  EXPECT_EQ(t.current_step(), 1);
  EXPECT_FLOAT_EQ(t.steps()[1].fraction(), 0.5f);
  EXPECT_FALSE(t.steps()[1].complete);
  EXPECT_DOUBLE_EQ(t.fraction(), 1.5 / 10.0);
  EXPECT_NEAR(t.eta_s(3.0), 3.0 * (1 - 0.15) / 0.15, 1e-9);
  for (int k = 1; k < kRemovalStepCount; ++k) t.update({RemovalStep(k), 1, 1, ""}, 3.0 + k);
  EXPECT_TRUE(t.all_complete());
  EXPECT_DOUBLE_EQ(t.fraction(), 1.0);
  EXPECT_EQ(t.eta_s(10.0), 0.0);

  // After a cancel request a step that reports 100 % as it stops is not complete.
  RemovalProgressTracker c(cost);
  c.update({RemovalStep::Selection, 1, 1, ""}, 0.1);
  c.update({RemovalStep::LightingMasks, 3, 40, "r_003"}, 0.2);
  c.freeze();
  c.update({RemovalStep::LightingMasks, 1, 1, ""}, 0.3);
  EXPECT_TRUE(c.steps()[0].complete);
  EXPECT_FALSE(c.steps()[1].complete);
  EXPECT_FALSE(c.all_complete());

  // The cost model: the fine-tune dominates a long schedule; skipped lighting masks cost next to nothing.
  const RemovalCostModel e = RemovalCostModel::estimate(40, 4000, false, true);
  EXPECT_GT(e.weight[int(RemovalStep::FineTune)], 10 * e.weight[int(RemovalStep::InpaintMasks)]);
  EXPECT_LT(e.weight[int(RemovalStep::LightingMasks)], 0.1);
}

namespace {

// A tiny radiance run of the embedded scene with a selection of the Gaussians nearest the scene's middle.
fs::path tiny_run_with_selection() {
  const fs::path run = test::scratch_dir("studio_removal_session") / "run";
  TrainerSession t;
  TrainRequest rq;
  rq.data = test::resource_dir() / "default_scene";
  rq.run_dir = run;
  rq.config.input.resolution = 32;
  rq.config.init.random_points = 300;
  rq.config.init.random_box_ratio = 0.15f;
  rq.config.device = DeviceChoice::CPU;
  rq.config.bookkeeping.checkpoint_interval = 0;
  rq.iterations = 10;
  t.start(rq);
  EXPECT_EQ(t.wait(std::chrono::seconds(120)), JobState::Done) << t.status();
  const GaussianModel model = load_run_model(run, Device::CPU);
  const SelectionPoints pts = selection_points(model);
  glm::vec3 mean(0.0f);
  for (const glm::vec3& p : pts.position) mean += p / float(pts.size());
  std::vector<std::pair<float, std::size_t>> by_distance;
  for (std::size_t i = 0; i < pts.size(); ++i) by_distance.emplace_back(glm::length(pts.position[i] - mean), i);
  std::sort(by_distance.begin(), by_distance.end());
  SelectionMask mask(pts.size(), 0);
  for (std::size_t k = 0; k < pts.size() / 10; ++k) mask[by_distance[k].second] = 1;
  SelectionRecord record;
  record.method = "test";
  record.model_fingerprint = model_fingerprint(model);
  write_selection(selection_json_path(run), record, mask);
  return run;
}

}  // namespace

TEST(StudioRemovalSession, FailsCancelsResumesAndCompletes) {
  RemovalSession s;
  EXPECT_EQ(s.state(), JobState::Idle);
  EXPECT_THROW(s.start(fs::path(), {}), Error);
  // Not a run: the Error state with the pipeline's reason.
  s.start(test::scratch_dir("studio_removal_not_a_run"), {});
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Error);
  EXPECT_NE(s.status().find("config.json"), std::string::npos) << s.status();

  const fs::path run = tiny_run_with_selection();
  RemovalOptions o;
  o.finetune_iterations = 5;
  o.device = DeviceChoice::CPU;
  s.start(run, o);
  EXPECT_THROW(s.start(run, o), Error);  // one at a time
  s.cancel();
  EXPECT_EQ(s.state(), JobState::Cancelling);
  EXPECT_EQ(s.wait(std::chrono::seconds(120)), JobState::Cancelled) << s.status();
  EXPECT_FALSE(s.progress().all_complete());
  EXPECT_FALSE(fs::exists(run / "removal" / "report.json"));
  EXPECT_EQ(s.runs_ended(), 2u);

  s.start(run, o);
  EXPECT_EQ(s.wait(std::chrono::seconds(300)), JobState::Done) << s.status();
  const RemovalProgressTracker p = s.progress();
  EXPECT_TRUE(p.all_complete());
  EXPECT_DOUBLE_EQ(p.fraction(), 1.0);
  ASSERT_TRUE(s.report().has_value());
  EXPECT_EQ(s.report()->finetune_iterations, 5);
  EXPECT_GT(s.report()->selected, 0u);
  EXPECT_NE(s.status().find("done:"), std::string::npos) << s.status();
  for (const char* f : {"report.json", "config.json", "point_cloud.ply", "reference.json"})
    EXPECT_TRUE(fs::exists(run / "removal" / f)) << f;
  EXPECT_GT(s.elapsed_s(), 0.0);
}
