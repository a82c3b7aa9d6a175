// The stability bench's finite-output verdict (train/setup/finite_outputs.h): a NaN or Inf planted in a
// PLY, a checkpoint's parameters or Adam moments, an intrinsic run's environment map, or the metrics of
// `goris eval` is flagged with the file and what is not finite; clean outputs pass.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/io/json_file.h"
#include "core/io/ply.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_folder.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/setup/finite_outputs.h"
#include "train/setup/run_renderer.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;
using namespace goris;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

GaussianModel small_model(int n = 5) {
  GaussianModel m(Device::CPU);
  m.allocate(size_t(n));
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    for (size_t i = 0; i < t.value.size(); ++i) t.value[i] = 0.01f * float(i % 17) - 0.05f;
  }
  for (int i = 0; i < n; ++i) m.values(Param::Rotation)[i * 4] = 1.0f;
  return m;
}

TrainerState state_of(GaussianModel m) {
  TrainerState s = Trainer::initial_state(TrainConfig{}, std::move(m));
  s.stats.reset(s.model.count(), Device::CPU);
  s.iteration = 10;
  return s;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& what) {
  for (const auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

}  // namespace

TEST(FiniteOutputs, PlantedNanInAPlyIsFlaggedWithVertexAndProperty) {
  const fs::path dir = test::scratch_dir("finite_outputs_ply");
  GaussianModel m = small_model();
  write_ply(dir / "clean.ply", m.to_ply());
  EXPECT_TRUE(ply_finite_problems(dir / "clean.ply").empty()) << joined(ply_finite_problems(dir / "clean.ply"));

  m.values(Param::OpacityLogit)[3] = kNaN;
  write_ply(dir / "nan.ply", m.to_ply());
  const auto problems = ply_finite_problems(dir / "nan.ply");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("nan.ply"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("opacity"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("3"), std::string::npos) << problems[0];
}

TEST(FiniteOutputs, ModelProblemsNameParameterMomentAndGaussian) {
  GaussianModel m = small_model();
  EXPECT_TRUE(model_finite_problems(m, "model").empty());
  m.tensor(Param::Sh).adam_v[2 * 48 + 5] = kInf;
  m.values(Param::Position)[4 * 3] = kNaN;
  m.values(Param::Position)[4 * 3 + 1] = kNaN;
  const auto problems = model_finite_problems(m, "model");
  ASSERT_EQ(problems.size(), 2u) << joined(problems);
  EXPECT_TRUE(any_contains(problems, "parameter 'position' value has 2 non-finite values (first at Gaussian 4)"))
      << joined(problems);
  EXPECT_TRUE(any_contains(problems, "Adam second moment has 1 non-finite value (first at Gaussian 2)"))
      << joined(problems);
}

TEST(FiniteOutputs, RunFolderChecksTheLatestCheckpointAndThePly) {
  const fs::path run = test::scratch_dir("finite_outputs_run");
  fs::create_directories(run / "checkpoints");
  TrainerState s = state_of(small_model());
  s.skipped_steps = 2;
  write_checkpoint(checkpoint_path(run, 10), TrainConfig{}, s);
  write_ply(run_ply_path(run), s.model.to_ply());
  RunFiniteReport r = check_run_finite(run);
  EXPECT_TRUE(r.problems.empty()) << joined(r.problems);
  EXPECT_TRUE(r.has_checkpoint);
  EXPECT_EQ(r.skipped_steps, 2);
  EXPECT_EQ(r.checked.size(), 2u);

  // A later checkpoint with an Inf in an Adam moment: that one is checked, and named.
  s.model.tensor(Param::Rotation).adam_m[7] = -kInf;
  s.iteration = 20;
  write_checkpoint(checkpoint_path(run, 20), TrainConfig{}, s);
  r = check_run_finite(run);
  ASSERT_EQ(r.problems.size(), 1u) << joined(r.problems);
  EXPECT_NE(r.problems[0].find("iter_00000020"), std::string::npos) << r.problems[0];
  EXPECT_NE(r.problems[0].find("parameter 'rotation' Adam first moment"), std::string::npos) << r.problems[0];
}

TEST(FiniteOutputs, NanInAnIntrinsicRunsEnvironmentMapIsFlagged) {
  const fs::path run = test::scratch_dir("finite_outputs_env");
  fs::create_directories(run / "checkpoints");
  TrainConfig config;
  config.mode = TrainMode::Intrinsic;
  config.intrinsic.env_resolution = 4;
  config.intrinsic.net_hidden_layers = 1;
  write_run_config(run, config);
  const TrainerState s = state_of(small_model());
  const fs::path ck = checkpoint_path(run, 10);
  write_checkpoint(ck, config, s);
  auto renderer = make_renderer(config, 1.0f, Device::CPU);
  auto save_state = [&] {
    const std::string bytes = renderer->save_own_state();
    write_file_bytes(renderer_state_path(ck), bytes.data(), bytes.size());
  };
  save_state();
  RunFiniteReport r = check_run_finite(run);
  EXPECT_TRUE(r.problems.empty()) << joined(r.problems);
  EXPECT_EQ(r.checked.size(), 2u);  // the checkpoint and its renderer state

  as_intrinsic(renderer.get())->environment().params()[5] = kNaN;
  save_state();
  r = check_run_finite(run);
  ASSERT_EQ(r.problems.size(), 1u) << joined(r.problems);
  EXPECT_NE(r.problems[0].find(".renderer"), std::string::npos) << r.problems[0];
  EXPECT_NE(r.problems[0].find("non-finite"), std::string::npos) << r.problems[0];
}

TEST(FiniteOutputs, MetricsNeedFiniteMeansAndFiniteRenders) {
  const fs::path dir = test::scratch_dir("finite_outputs_metrics");
  const fs::path m = dir / "metrics.json";
  nlohmann::json good = {{"psnr", 21.5}, {"ssim", 0.8}, {"non_finite_values", 0},
                         {"masked", {{"psnr", 15.0}, {"ssim", 0.5}, {"views", 4}}}};
  write_json_file(m, good);
  EXPECT_TRUE(metrics_finite_problems(m).empty()) << joined(metrics_finite_problems(m));

  nlohmann::json no_masked = good;  // no masked views: null masked means are fine
  no_masked["masked"] = {{"psnr", nullptr}, {"ssim", nullptr}, {"views", 0}};
  write_json_file(m, no_masked);
  EXPECT_TRUE(metrics_finite_problems(m).empty()) << joined(metrics_finite_problems(m));

  nlohmann::json bad = good;
  bad["psnr"] = nullptr;  // what a NaN mean becomes in JSON
  bad["masked"]["ssim"] = nullptr;
  bad["non_finite_values"] = 12;
  write_json_file(m, bad);
  const auto problems = metrics_finite_problems(m);
  EXPECT_EQ(problems.size(), 3u) << joined(problems);
  EXPECT_TRUE(any_contains(problems, "psnr is not a finite number (null)")) << joined(problems);
  EXPECT_TRUE(any_contains(problems, "masked ssim")) << joined(problems);
  EXPECT_TRUE(any_contains(problems, "hold 12 non-finite values")) << joined(problems);

  const std::string broken = "{\"psnr\": 3";
  write_file_bytes(m, broken.data(), broken.size());
  EXPECT_TRUE(any_contains(metrics_finite_problems(m), "not a JSON object"));
}
