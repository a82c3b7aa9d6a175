// The editor's document and its scripted mode without a window: opening (in the background), snapping to
// data set cameras, channel choices, clicks, training through the session, and the script runner driving
// them frame by frame with its waiting rules and line-numbered errors.
#include <chrono>
#include <thread>

#include "train/run/run_folder.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "ui/document/app_state.h"
#include "ui/display/display_renderer.h"
#include "ui/script/script_runner.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

fs::path scene_path() { return test::resource_dir() / "default_scene"; }

void poll_until(AppState& st, const std::function<bool()>& done, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    ASSERT_LT(std::chrono::steady_clock::now(), end) << "timed out";
    st.poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

// A host standing in for the window: settled whenever nothing runs; screenshots are recorded.
class FakeHost final : public ScriptHost {
 public:
  explicit FakeHost(AppState& st) : st_(st) {}
  AppState& state() override { return st_; }
  bool settled() const override {
    return !st_.opening() && !st_.session().active();
  }
  glm::vec2 main_image_size() const override { return {96, 96}; }
  void request_screenshot(const fs::path& png) override {
    shots.push_back(png);
    pending_ = 1;
  }
  bool screenshot_pending() const override { return pending_ > 0; }
  std::optional<std::string> screenshot_error() const override { return error; }
  void quit() override { quitted = true; }
  void end_frame() {
    if (pending_ > 0) --pending_;
  }

  std::vector<fs::path> shots;
  std::optional<std::string> error;
  bool quitted = false;

 private:
  AppState& st_;
  int pending_ = 0;
};

std::string& last_error() {
  static std::string e;
  return e;
}

// Runs a script to its end like the editor's frame loop; returns the final status.
ScriptRunner::Status run_script(AppState& st, FakeHost& host, const std::string& text, int max_frames = 200000) {
  ScriptRunner r(parse_script(text, "t.txt"), "t.txt");
  for (int i = 0; i < max_frames && r.status() == ScriptRunner::Status::Running; ++i) {
    st.poll();
    r.step(host);
    host.end_frame();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (r.status() == ScriptRunner::Status::Failed) last_error() = r.error();
  return r.status();
}

}  // namespace

TEST(StudioAppState, OpensSnapsAndChoosesChannels) {
  StudioSettings settings;
  settings.grid_channels = {"normal", "glossy", "depth"};  // kept: the tile says why until it can show it
  AppState st(settings);
  ASSERT_EQ(st.grid_channels.size(), 3u);
  EXPECT_EQ(st.grid_channels[1], Channel::Glossy);
  EXPECT_NE(std::string(st.channel_unavailable(Channel::Glossy)).find("needs an intrinsic run"), std::string::npos);
  EXPECT_THROW(st.snap(0, false), Error);  // nothing open
  EXPECT_THROW(st.start_training(5, true), Error);
  EXPECT_THROW(st.click(1, 1, 10, 10), Error);  // no frame

  st.open(scene_path());
  EXPECT_TRUE(st.opening());
  EXPECT_THROW(st.open(scene_path()), Error);  // one at a time
  poll_until(
      st, [&] { return !st.opening(); }, 30);
  ASSERT_NE(st.scene(), nullptr) << st.open_error();
  EXPECT_EQ(settings.recent_paths.front(), fs::absolute(scene_path()).lexically_normal().string());
  EXPECT_NE(st.last_message().find("opened data set"), std::string::npos);
  EXPECT_EQ(st.scene_version(), 1u);
  // Opening snaps to the first training camera; the render camera is that camera, fitted and capped.
  ASSERT_TRUE(st.snapped.has_value());
  EXPECT_EQ(st.snapped_name, "train 0 (r_000)");
  settings.display_max_side = 64;
  const Camera c = st.render_camera(300, 200);
  EXPECT_EQ(c.width, 64);  // 128 x 128 camera in a 300 x 200 box: 200 x 200, capped to 64
  EXPECT_EQ(c.height, 64);
  EXPECT_EQ(c.R, st.snapped->R);
  st.snap(5, true);
  EXPECT_EQ(st.snapped_name, "test 5 (r_005)");
  EXPECT_THROW(st.snap(40, false), Error);
  st.camera_moved();
  EXPECT_FALSE(st.snapped.has_value());
  const Camera free = st.render_camera(300, 200);
  EXPECT_EQ(free.width, 64);
  EXPECT_EQ(free.height, 43);

  st.set_channel(-1, Channel::Depth);
  EXPECT_EQ(st.main_channel, Channel::Depth);
  EXPECT_EQ(settings.main_channel, "depth");
  st.set_channel(2, Channel::Alpha);
  EXPECT_EQ(settings.grid_channels[2], "alpha");
  EXPECT_THROW(st.set_channel(3, Channel::Alpha), Error);  // no such tile
  try {
    st.set_channel(0, Channel::LightingMask);
    FAIL() << "an unavailable channel was shown";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs removal"), std::string::npos);
  }
  st.set_grid_count(6);
  EXPECT_EQ(st.grid_channels.size(), 6u);
  EXPECT_EQ(settings.grid_channels.size(), 6u);
  st.set_grid_count(99);
  EXPECT_EQ(st.grid_channels.size(), size_t(AppState::kMaxGrid));
  st.set_compare(CompareMode::Slider, 1.5f);
  EXPECT_EQ(st.compare_split, 1.0f);
  EXPECT_EQ(settings.compare_mode, "slider");

  // Opening again replaces the scene (same address, new version) and snaps to its first camera.
  st.open(scene_path());
  poll_until(
      st, [&] { return !st.opening(); }, 30);
  EXPECT_EQ(st.scene_version(), 2u);
  EXPECT_EQ(st.snapped_name, "train 0 (r_000)");
  // A failed open keeps the scene and says why.
  st.open(scene_path() / "missing");
  poll_until(
      st, [&] { return !st.opening(); }, 30);
  EXPECT_EQ(st.scene_version(), 2u);
  EXPECT_NE(st.open_error().find("no such file or folder"), std::string::npos) << st.open_error();
  EXPECT_TRUE(st.last_message_is_error());
}

TEST(StudioAppState, ScriptRunsTrainingAndReportsErrors) {
  const fs::path dir = test::scratch_dir("studio_app_script");
  StudioSettings settings;
  settings.train_resolution = 32;
  settings.train_device = "cpu";
  AppState st(settings);
  FakeHost host(st);
  const std::string script = "open " + scene_path().string() + "\nout " + (dir / "run").string() +
                             "\nset random_init_points 300\nset checkpoint_interval 0\ntrain 6\ntrain 4\n"
                             "screenshot " +
                             (dir / "a.png").string() + "\nwait_frames 3\nquit\nwait_frames 1\n";
  ASSERT_EQ(run_script(st, host, script), ScriptRunner::Status::Finished) << last_error();
  EXPECT_TRUE(host.quitted);
  EXPECT_EQ(st.session().progress().iteration, 10);
  EXPECT_EQ(read_run_config(dir / "run").iterations, 10);
  EXPECT_EQ(read_run_config(dir / "run").init.random_points, 300);
  ASSERT_EQ(host.shots.size(), 1u);
  EXPECT_EQ(host.shots[0], dir / "a.png");
  ASSERT_NE(st.model(), nullptr);
  EXPECT_EQ(st.model()->iteration(), 10);  // the viewports show the last snapshot
  EXPECT_NE(st.last_message().find("done: 10 iterations"), std::string::npos) << st.last_message();

  // Another editor's `out` at that finished run refuses to train it over with new settings, as the CLI does.
  {
    AppState other(settings);
    FakeHost other_host(other);
    EXPECT_EQ(run_script(other, other_host, "open " + scene_path().string() + "\nout " + (dir / "run").string() +
                                                "\nset random_init_points 200\ntrain 3\n"),
              ScriptRunner::Status::Failed);
    EXPECT_NE(last_error().find("already holds a training run"), std::string::npos) << last_error();
    EXPECT_EQ(read_run_config(dir / "run").init.random_points, 300);
    // A missing parent folder is refused, not created.
    EXPECT_EQ(run_script(other, other_host, "out " + (dir / "missing" / "run").string() + "\ntrain 3\n"),
              ScriptRunner::Status::Failed);
    EXPECT_NE(last_error().find("does not exist"), std::string::npos) << last_error();
    EXPECT_FALSE(fs::exists(dir / "missing"));
  }

  // Failures name the line and the action.
  EXPECT_EQ(run_script(st, host, "wait_frames 1\nset no_such_key 1\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("t.txt:2: set: "), std::string::npos) << last_error();
  EXPECT_EQ(run_script(st, host, "open " + (dir / "nope").string() + "\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("t.txt:1: open: "), std::string::npos) << last_error();
  EXPECT_NE(last_error().find("no such file or folder"), std::string::npos) << last_error();
  EXPECT_EQ(run_script(st, host, "snap 99\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("t.txt:1: snap: "), std::string::npos) << last_error();
  EXPECT_EQ(run_script(st, host, "click 5 5\n"), ScriptRunner::Status::Failed);  // no rendered frame here
  EXPECT_NE(last_error().find("t.txt:1: click: "), std::string::npos) << last_error();
  host.error = "disk full";
  EXPECT_EQ(run_script(st, host, "wait_frames 0\nscreenshot x.png\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("t.txt:2: screenshot: disk full"), std::string::npos) << last_error();
  host.error.reset();
  // A training failure ends the script at its line.
  EXPECT_EQ(run_script(st, host, "out " + (dir / "run2").string() + "\nset device \"cuda\"\ntrain 3\n"),
            cuda_device_count() > 0 ? ScriptRunner::Status::Finished : ScriptRunner::Status::Failed);
  if (cuda_device_count() == 0) EXPECT_NE(last_error().find("t.txt:3: train: "), std::string::npos) << last_error();
}

// Selecting and removing through the script actions, as the GUI test does in a window: a tiny intrinsic
// run, a frame of the snapped training camera, selection edits with undo / redo, save, removal, and the
// removal's mask channels for training cameras only.
TEST(StudioAppState, ScriptSelectsAndRemoves) {
  const fs::path dir = test::scratch_dir("studio_app_select_remove");
  StudioSettings settings;
  settings.train_resolution = 32;
  settings.train_device = "cpu";
  settings.train_mode = "auto";
  AppState st(settings);
  FakeHost host(st);
  ASSERT_EQ(run_script(st, host,
                       "open " + scene_path().string() + "\nout " + (dir / "run").string() +
                           "\nset random_init_points 400\nset random_init_box_ratio 0.15\nset checkpoint_interval 0"
                           "\nset intrinsic_env_resolution 8\ntrain 8\n"),
            ScriptRunner::Status::Finished)
      << last_error();
  ASSERT_NE(st.model(), nullptr);
  EXPECT_TRUE(st.model()->intrinsic());
  EXPECT_EQ(st.channel_unavailable(Channel::Glossy), nullptr);
  EXPECT_EQ(st.current_run(), dir / "run");
  // The frame the window would show (the fake host renders none).
  DisplayRenderer dr;
  ASSERT_TRUE(st.snapped.has_value());
  st.frame = std::make_shared<DisplayFrame>(dr.render(*st.model(), st.snapped->resized(64, 64), nullptr));
  ASSERT_TRUE(st.frame->intrinsic());

  // Masks select; undo empties, redo restores; a plain click (anywhere) never fails the script.
  ASSERT_EQ(run_script(st, host, "select_masks\n"), ScriptRunner::Status::Finished) << last_error();
  const std::size_t by_masks = st.selection().view().selected;
  EXPECT_GT(by_masks, 0u);
  ASSERT_EQ(run_script(st, host, "undo\n"), ScriptRunner::Status::Finished) << last_error();
  EXPECT_EQ(st.selection().view().selected, 0u);
  EXPECT_EQ(run_script(st, host, "undo\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("t.txt:1: undo: undo: nothing to undo"), std::string::npos) << last_error();
  ASSERT_EQ(run_script(st, host, "redo\nclick 2 2\nselect_grow 0.2\nundo\n"), ScriptRunner::Status::Finished)
      << last_error();
  EXPECT_EQ(st.selection().view().selected, by_masks);
  EXPECT_EQ(run_script(st, host, "select_click 0% 0%\n"), ScriptRunner::Status::Failed);  // a corner: background
  EXPECT_NE(last_error().find("nothing there"), std::string::npos) << last_error();
  EXPECT_EQ(st.selection().view().selected, by_masks);

  // Stage 2: the unsaved selection is saved first, every step completes, the mask channels appear.
  EXPECT_NE(st.channel_unavailable(Channel::InpaintMask), nullptr);
  EXPECT_EQ(run_script(st, host, "remove_cancel\n"), ScriptRunner::Status::Failed);  // nothing runs
  EXPECT_NE(last_error().find("no removal is running"), std::string::npos) << last_error();
  EXPECT_EQ(run_script(st, host, "remove_wait\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("no removal was started"), std::string::npos) << last_error();
  // Started, cancelled at once: stopped, not complete; the next removal resumes and completes.
  ASSERT_EQ(run_script(st, host, "remove_start 3\nremove_cancel\n"), ScriptRunner::Status::Finished) << last_error();
  EXPECT_EQ(st.removal().state(), JobState::Cancelled);
  EXPECT_EQ(run_script(st, host, "expect_step_complete\n"), ScriptRunner::Status::Failed);
  ASSERT_EQ(run_script(st, host, "remove 3\nexpect_step_complete\nremove_wait\n"), ScriptRunner::Status::Finished)
      << last_error();
  EXPECT_TRUE(fs::exists(dir / "run" / "selection.json"));
  EXPECT_TRUE(fs::exists(dir / "run" / "removal" / "report.json"));
  // The cleaned scene replaces the run in the viewports, the view kept; before / after shows the run again.
  EXPECT_EQ(st.current_run(), dir / "run" / "removal");
  ASSERT_TRUE(st.has_before());
  EXPECT_EQ(st.model(), st.scene()->model);
  EXPECT_GT(st.scene()->before_model->count(), st.model()->count());
  EXPECT_EQ(st.removal_result(), dir / "run" / "removal");  // what `export_from removal` exports
  ASSERT_EQ(run_script(st, host, "before_after before\n"), ScriptRunner::Status::Finished) << last_error();
  EXPECT_EQ(st.model(), st.scene()->before_model);
  ASSERT_EQ(run_script(st, host, "before_after after\ncompare_with photo\n"), ScriptRunner::Status::Finished)
      << last_error();
  EXPECT_EQ(st.model(), st.scene()->model);
  EXPECT_FALSE(st.compare_with_before);
  EXPECT_EQ(st.removal_masks_dir(), dir / "run" / "removal");
  EXPECT_EQ(st.channel_unavailable(Channel::InpaintMask), nullptr);
  st.set_channel(0, Channel::InpaintMask);
  st.snap(0, true);  // a test camera: no masks there
  EXPECT_NE(std::string(st.channel_unavailable(Channel::LightingMask)).find("training cameras"), std::string::npos);
  EXPECT_THROW(st.set_channel(1, Channel::LightingMask), Error);
  // expect_step_complete fails before any complete removal.
  AppState fresh(settings);
  FakeHost fresh_host(fresh);
  EXPECT_EQ(run_script(fresh, fresh_host, "expect_step_complete\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("not every stage-2 step reached 100 %: selection at 0 %"), std::string::npos)
      << last_error();
  EXPECT_EQ(run_script(fresh, fresh_host, "before_after before\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("not a cleaned scene"), std::string::npos) << last_error();
  EXPECT_EQ(run_script(fresh, fresh_host, "select_labels\n"), ScriptRunner::Status::Failed);
  EXPECT_NE(last_error().find("nothing to select in"), std::string::npos) << last_error();
}
