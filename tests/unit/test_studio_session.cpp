// The editor's training session (ui/document/trainer_session.h): its state machine on a real (tiny) training of the
// embedded scene, the run folder it writes (as `goris train`), snapshots and history, continuing in memory
// and from the folder's checkpoint, and failures that end in the Error state with the reason.
#include <chrono>
#include <filesystem>
#include <thread>

#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_folder.h"
#include "ui/document/trainer_session.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

TrainRequest tiny_request(const fs::path& run, int iterations) {
  TrainRequest rq;
  rq.data = test::resource_dir() / "default_scene";
  rq.run_dir = run;
  rq.config.input.resolution = 32;
  rq.config.init.random_points = 400;
  rq.config.device = DeviceChoice::CPU;
  rq.config.bookkeeping.checkpoint_interval = 0;
  rq.iterations = iterations;
  return rq;
}

// Polls until `pred` holds (the GUI's way of waiting) or fails the test after `seconds`.
template <class F>
void wait_for(F pred, double seconds, const char* what) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!pred()) {
    ASSERT_LT(std::chrono::steady_clock::now(), end) << "timed out waiting for " << what;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace

TEST(StudioSession, TrainsIntoARunFolderAndPublishes) {
  const fs::path run = test::scratch_dir("studio_session_train") / "run";
  SessionOptions opt;
  opt.snapshot_every = 4;
  opt.snapshot_interval_s = 100;  // by iterations only, to count them
  TrainerSession s(opt);
  EXPECT_EQ(s.state(), JobState::Idle);
  EXPECT_EQ(s.snapshot(), nullptr);
  s.start(tiny_request(run, 12));
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
  EXPECT_NE(s.status().find("done: 12 iterations"), std::string::npos) << s.status();
  EXPECT_EQ(s.progress().iteration, 12);
  EXPECT_EQ(s.progress().total, 12);
  for (const char* f : {"config.json", "log.csv", "point_cloud.ply"}) EXPECT_TRUE(fs::exists(run / f)) << f;
  EXPECT_TRUE(latest_checkpoint(run).has_value());
  EXPECT_EQ(read_run_config(run).iterations, 12);

  // Snapshots: the initial one, every 4 iterations, and the last; the last shows iteration 12.
  ASSERT_NE(s.snapshot(), nullptr);
  EXPECT_EQ(s.snapshot()->iteration(), 12);
  EXPECT_EQ(s.snapshot()->count(), s.progress().gaussians);
  EXPECT_EQ(s.snapshot_version(), 4u);  // 0, 4, 8, 12
  const TrainingHistory h = s.history();
  ASSERT_EQ(h.samples().size(), 12u);
  EXPECT_EQ(h.samples().front().iteration, 1);
  EXPECT_EQ(h.samples().back().iteration, 12);
  EXPECT_GT(h.samples().back().loss, 0.0f);

  // Done -> start again: continues the trainer in memory (more iterations), the folder follows.
  TrainRequest more = tiny_request(run, 5);
  more.more = true;
  s.start(more);
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
  EXPECT_EQ(s.progress().iteration, 17);
  EXPECT_EQ(read_run_config(run).iterations, 17);
  EXPECT_EQ(s.history().samples().back().iteration, 17);
  // A target the run has already reached is an error, not a silent no-op.
  s.start(tiny_request(run, 10));
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Error);
  EXPECT_NE(s.status().find("already trained for 17"), std::string::npos) << s.status();

  // A new session on the same folder resumes from its checkpoint (like `goris train --resume`).
  TrainerSession again;
  TrainRequest resume = tiny_request(run, 3);
  resume.more = true;
  again.start(resume);
  EXPECT_EQ(again.wait(std::chrono::seconds(60)), JobState::Done) << again.status();
  EXPECT_EQ(again.progress().iteration, 20);
}

TEST(StudioSession, ARunStoppedBeforeWritingItsModelIsFinishedNotRefused) {
  const fs::path run = test::scratch_dir("studio_session_unwritten") / "run";
  {
    TrainerSession s;
    s.start(tiny_request(run, 6));
    ASSERT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
  }
  const fs::path ck = *latest_checkpoint(run);
  // As if stopped after its last checkpoint but before its model: point_cloud.ply older than the checkpoint.
  fs::last_write_time(run_ply_path(run), fs::last_write_time(ck) - std::chrono::hours(1));
  ASSERT_FALSE(run_outputs_written_after(run, ck, read_run_config(run)));
  TrainerSession s;
  s.start(tiny_request(run, 6));
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
  EXPECT_NE(s.status().find("done: 6 iterations"), std::string::npos) << s.status();
  EXPECT_TRUE(run_outputs_written_after(run, *latest_checkpoint(run), read_run_config(run)));
  // Finished now: the same request is refused as already trained.
  TrainerSession t;
  t.start(tiny_request(run, 6));
  EXPECT_EQ(t.wait(std::chrono::seconds(60)), JobState::Error);
  EXPECT_NE(t.status().find("already trained for 6"), std::string::npos) << t.status();
}

TEST(StudioSession, PauseResumeStop) {
  const fs::path run = test::scratch_dir("studio_session_pause") / "run";
  TrainerSession s;
  s.pause();  // nothing to pause: stays idle
  s.stop();
  EXPECT_EQ(s.state(), JobState::Idle);
  s.start(tiny_request(run, 1000000));
  EXPECT_THROW(s.start(tiny_request(run, 10)), Error);  // busy
  wait_for([&] { return s.progress().iteration >= 2; }, 60, "two iterations");
  s.pause();
  EXPECT_EQ(s.state(), JobState::Paused);
  wait_for([&] { return s.status().rfind("paused", 0) == 0; }, 30, "the worker to pause");
  const int at = s.progress().iteration;
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_EQ(s.progress().iteration, at);  // nothing runs while paused
  s.resume();
  EXPECT_EQ(s.state(), JobState::Running);
  wait_for([&] { return s.progress().iteration >= at + 2; }, 60, "training to go on");
  s.stop();
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
  EXPECT_NE(s.status().find("stopped at iteration"), std::string::npos) << s.status();
  const auto ck = latest_checkpoint(run);
  ASSERT_TRUE(ck.has_value());
  EXPECT_EQ(*ck, checkpoint_path(run, s.progress().iteration));
  EXPECT_FALSE(fs::exists(run / "point_cloud.ply"));  // only a finished run writes its final model

  // Stopping while paused ends the run too.
  s.start([&] {
    TrainRequest rq = tiny_request(run, 3);
    rq.more = true;
    rq.iterations = 1000000;
    return rq;
  }());
  wait_for([&] { return s.progress().iteration > at + 2; }, 60, "the restarted run");
  s.pause();
  s.stop();
  EXPECT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
}

TEST(StudioSession, FailuresEndInErrorWithTheReason) {
  const fs::path dir = test::scratch_dir("studio_session_errors");
  TrainerSession s;
  TrainRequest rq = tiny_request(dir / "run", 5);
  rq.data = dir / "no_such_data";
  s.start(rq);
  EXPECT_EQ(s.wait(std::chrono::seconds(30)), JobState::Error);
  EXPECT_NE(s.status().find("no_such_data"), std::string::npos) << s.status();

  // A folder that holds another data set's run is refused.
  rq = tiny_request(dir / "run2", 2);
  s.start(rq);
  ASSERT_EQ(s.wait(std::chrono::seconds(60)), JobState::Done) << s.status();
  TrainerSession other;
  TrainRequest wrong = tiny_request(dir / "run2", 5);
  wrong.data = test::resource_dir();
  other.start(wrong);
  EXPECT_EQ(other.wait(std::chrono::seconds(30)), JobState::Error);
  EXPECT_NE(other.status().find("was trained on"), std::string::npos) << other.status();

  EXPECT_THROW(s.start(tiny_request(dir / "run3", 0)), Error);
  EXPECT_THROW(s.start(tiny_request(fs::path(), 5)), Error);
}

TEST(StudioSession, AutoModeTrainsIntrinsicLikeTheCli) {
  // The embedded scene has glossy masks: --mode auto picks intrinsic, whose run keeps its environment map.
  const fs::path run = test::scratch_dir("studio_session_auto") / "run";
  TrainRequest rq = tiny_request(run, 3);
  rq.config.mode = TrainMode::Auto;
  TrainerSession s;
  s.start(rq);
  ASSERT_EQ(s.wait(std::chrono::seconds(120)), JobState::Done) << s.status();
  EXPECT_EQ(read_run_config(run).mode, TrainMode::Intrinsic);
  EXPECT_TRUE(fs::exists(run / "environment.png"));
  EXPECT_TRUE(fs::exists(run / "point_cloud.ply"));
  // Its snapshots carry what the display shades them with: the run's settings and the renderer's state.
  ASSERT_NE(s.snapshot(), nullptr);
  EXPECT_TRUE(s.snapshot()->intrinsic());
  EXPECT_EQ(s.snapshot()->shading()->config.mode, TrainMode::Intrinsic);
  EXPECT_GT(s.snapshot()->renderer_state()->size(), 0u);
  // Resuming restores the renderer's own state (environment map, net) from the checkpoint.
  TrainerSession again;
  TrainRequest more = tiny_request(run, 2);
  more.more = true;
  again.start(more);
  EXPECT_EQ(again.wait(std::chrono::seconds(120)), JobState::Done) << again.status();
  EXPECT_EQ(again.progress().iteration, 5);
}
