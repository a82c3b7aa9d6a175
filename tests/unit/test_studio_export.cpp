// The editor's exports without a window: the export worker (ui/document/export_job.h) on a tiny intrinsic run of the
// embedded scene (every part written and readable, an unwritable path failing before any work, cancel and
// finish-early), the Export dialog's remembered choices (settings, paths relative to the run folder), and
// the script's export actions going through AppState::start_export.
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "core/io/image.h"
#include "core/io/ply.h"
#include "core/io/splat_compare.h"
#include "core/io/splat_formats.h"
#include "train/run/run_folder.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "ui/document/app_state.h"
#include "ui/document/export_job.h"
#include "ui/script/script.h"
#include "ui/script/script_runner.h"
#include "ui/document/settings_store.h"
#include "ui/document/trainer_session.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

// A tiny intrinsic run of the embedded scene, trained once per test program, in a folder of the first test
// that asks: ctest runs each test as its own process, two at a time, and a shared folder raced (one
// process's scratch_dir emptied it while the other trained into it).
const fs::path& tiny_intrinsic_run() {
  static const fs::path run = [] {
    const std::string test_name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    const fs::path r = test::scratch_dir("studio_export_run_" + test_name) / "run";
    TrainerSession t;
    TrainRequest rq;
    rq.data = test::resource_dir() / "default_scene";
    rq.run_dir = r;
    rq.config.mode = TrainMode::Intrinsic;
    rq.config.input.resolution = 32;
    rq.config.init.random_points = 300;
    rq.config.init.random_box_ratio = 0.15f;
    rq.config.intrinsic.env_resolution = 8;
    rq.config.device = DeviceChoice::CPU;
    rq.config.bookkeeping.checkpoint_interval = 0;
    rq.iterations = 4;
    t.start(rq);
    EXPECT_EQ(t.wait(std::chrono::seconds(120)), JobState::Done) << t.status();
    return r;
  }();
  return run;
}

// Files a writer left behind (write_via_temp_file names them .STEM.tmpPID_N.EXT).
std::vector<std::string> temp_files(const fs::path& dir) {
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos) left.push_back(e.path().string());
  return left;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

// A script host standing in for the window: settled whenever nothing runs.
class FakeHost final : public ScriptHost {
 public:
  explicit FakeHost(AppState& st) : st_(st) {}
  AppState& state() override { return st_; }
  bool settled() const override {
    return !st_.opening() && !st_.session().active() && !st_.exporter().active() && st_.export_reported();
  }
  glm::vec2 main_image_size() const override { return {96, 96}; }
  void request_screenshot(const fs::path&) override {}
  bool screenshot_pending() const override { return false; }
  std::optional<std::string> screenshot_error() const override { return std::nullopt; }
  void quit() override {}

 private:
  AppState& st_;
};

// Runs a script to its end like the editor's frame loop; returns the error ("" when it finished).
std::string run_script(AppState& st, FakeHost& host, const std::string& text) {
  ScriptRunner r(parse_script(text, "t.txt"), "t.txt");
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (r.status() == ScriptRunner::Status::Running && std::chrono::steady_clock::now() < end) {
    st.poll();
    r.step(host);
    std::this_thread::sleep_for(std::chrono::microseconds(300));
  }
  if (r.status() == ScriptRunner::Status::Running) return "timed out";
  return r.status() == ScriptRunner::Status::Failed ? r.error() : "";
}

}  // namespace

TEST(StudioExportScript, ParsesTheExportActions) {
  const auto a = parse_script(
      "export_dialog\nexport_dialog close\nexport_from removal\nexport ply out/model.ply\n"
      "export baked \"my dir/baked.ply\" 300\nexport_start renders frames orbit 8\nexport renders r 5\n"
      "export renders r train\nexport_wait\nexport_cancel\nexpect_export_error cannot create\nexport\n",
      "s.txt");
  ASSERT_EQ(a.size(), 12u);
  EXPECT_EQ(a[0].kind, ScriptAction::Kind::ExportDialog);
  EXPECT_EQ(a[0].what, "open");
  EXPECT_EQ(a[1].what, "close");
  EXPECT_EQ(a[2].kind, ScriptAction::Kind::ExportFrom);
  EXPECT_EQ(a[2].what, "removal");
  EXPECT_EQ(a[3].kind, ScriptAction::Kind::Export);
  EXPECT_EQ(a[3].what, "ply");
  EXPECT_EQ(a[3].path, "out/model.ply");
  EXPECT_EQ(a[4].what, "baked");
  EXPECT_EQ(a[4].path, "my dir/baked.ply");
  EXPECT_EQ(a[4].count, 300);
  EXPECT_EQ(a[5].kind, ScriptAction::Kind::ExportStart);
  EXPECT_EQ(a[5].render_path, "orbit");
  EXPECT_EQ(a[5].count, 8);
  EXPECT_EQ(a[6].render_path, "test");
  EXPECT_EQ(a[6].count, 5);
  EXPECT_EQ(a[7].render_path, "train");
  EXPECT_EQ(a[7].count, 0);
  EXPECT_EQ(a[8].kind, ScriptAction::Kind::ExportWait);
  EXPECT_EQ(a[9].kind, ScriptAction::Kind::ExportCancel);
  EXPECT_EQ(a[10].kind, ScriptAction::Kind::ExpectExportError);
  EXPECT_EQ(a[10].text, "cannot create");
  EXPECT_EQ(a[11].kind, ScriptAction::Kind::Export);
  EXPECT_EQ(a[11].what, "");  // the dialog's choices as they stand

  auto error_of = [](const std::string& line) {
    try {
      parse_script(line, "s.txt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(error_of("export mesh a.obj").find("s.txt:1: export: unknown export 'mesh'"), std::string::npos);
  EXPECT_NE(error_of("export ply").find("expected 'export | export ply PATH"), std::string::npos);
  EXPECT_NE(error_of("export ply a.ply b.ply").find("expected 'export ply PATH'"), std::string::npos);
  EXPECT_NE(error_of("export baked b.ply 0").find("iteration count 0 is outside"), std::string::npos);
  EXPECT_NE(error_of("export renders d sideways").find("frame count 'sideways'"), std::string::npos);
  EXPECT_NE(error_of("export renders d orbit 3 4").find("expected 'export renders DIR"), std::string::npos);
  EXPECT_NE(error_of("export ply \"a b.ply").find("unmatched double quote"), std::string::npos);
  EXPECT_NE(error_of("export_from elsewhere").find("expected run or removal"), std::string::npos);
  EXPECT_NE(error_of("export_dialog maybe").find("expected open or close"), std::string::npos);
}

TEST(StudioExportSettings, RemembersTheDialogsChoices) {
  const fs::path dir = test::scratch_dir("studio_export_settings");
  StudioSettings s;
  s.export_ply = false;
  s.export_baked = s.export_renders = true;
  s.export_baked_path = "/elsewhere/b.ply";
  s.export_renders_dir = "shots";
  s.export_baked_iterations = 321;
  s.export_render_path = "orbit";
  s.export_frames = 12;
  s.export_baked_spz = s.export_baked_splat = s.export_baked_glb = true;
  save_settings(dir / "settings.json", s);
  const StudioSettings r = load_settings(dir / "settings.json");
  EXPECT_FALSE(r.export_ply);
  EXPECT_TRUE(r.export_baked && r.export_renders);
  EXPECT_EQ(r.export_ply_path, "export/model.ply");
  EXPECT_EQ(r.export_baked_path, "/elsewhere/b.ply");
  EXPECT_EQ(r.export_renders_dir, "shots");
  EXPECT_EQ(r.export_baked_iterations, 321);
  EXPECT_EQ(r.export_render_path, "orbit");
  EXPECT_EQ(r.export_frames, 12);
  EXPECT_TRUE(r.export_baked_spz && r.export_baked_splat && r.export_baked_glb);
  EXPECT_FALSE(r.export_baked_compressed_ply);

  std::ofstream(dir / "bad.json") << R"({"export_render_path": "sideways"})";
  try {
    load_settings(dir / "bad.json");
    FAIL() << "an unknown render path was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'export_render_path': unknown value 'sideways'"), std::string::npos)
        << e.what();
  }
  std::ofstream(dir / "bad2.json") << R"({"export_baked_iterations": 0})";
  EXPECT_THROW(load_settings(dir / "bad2.json"), Error);
}

TEST(StudioExportJob, WritesEveryPartAndTheFilesLoad) {
  const fs::path run = tiny_intrinsic_run();
  const fs::path out = test::scratch_dir("studio_export_all");
  const GaussianModel model = load_run_model(run, Device::CPU);
  ExportRequest rq;
  rq.run_dir = run;
  rq.ply = out / "model.ply";
  rq.baked = out / "baked.ply";
  rq.baked_iterations = 3;
  rq.renders = out / "frames";
  rq.render_path = RenderPath::Orbit;
  rq.frames = 3;
  rq.device = DeviceChoice::CPU;
  ExportJob job;
  job.start(rq);
  EXPECT_THROW(job.start(rq), Error);  // one at a time
  ASSERT_EQ(job.wait(std::chrono::seconds(120)), JobState::Done) << job.status();

  const GaussianPly ply = read_ply(rq.ply);
  EXPECT_EQ(ply.count, model.count());
  EXPECT_NE(ply.extra("roughness"), nullptr);  // the intrinsic attributes ride along
  const GaussianPly baked = read_ply(rq.baked);
  EXPECT_EQ(baked.count, model.count());
  EXPECT_EQ(baked.sh_degree, 3);
  EXPECT_TRUE(baked.extras.empty());
  const nlohmann::json bj = read_json(baked_json_path(rq.baked));
  EXPECT_EQ(bj["iterations"], 3);
  EXPECT_EQ(bj["stopped"], false);
  for (const char* f : {"frame_000.png", "frame_001.png", "frame_002.png"}) {
    const Image im = read_image(rq.renders / f);
    EXPECT_EQ(im.width, 32) << f;
    EXPECT_EQ(im.height, 32) << f;
  }
  EXPECT_TRUE(fs::exists(rq.renders / "contact_sheet.png"));
  EXPECT_TRUE(fs::exists(rq.renders / "cameras.json"));
  EXPECT_TRUE(temp_files(out).empty());

  // Progress and the outcome: every part complete, the paths in the status and the summary.
  const ExportProgress p = job.progress();
  for (int k = 0; k < kExportPartCount; ++k)
    EXPECT_TRUE(p.parts[size_t(k)].complete) << export_part_name(ExportPart(k));
  EXPECT_DOUBLE_EQ(p.fraction(), 1.0);
  const ExportResult r = job.result();
  ASSERT_EQ(r.written.size(), 4u);  // ply, baked ply, its json, the renders folder
  EXPECT_EQ(r.written[0], rq.ply);
  ASSERT_TRUE(r.baked.has_value());
  EXPECT_TRUE(r.baked->distilled);
  EXPECT_EQ(r.baked->distill.ply.count, 0u);  // the model is not kept in the result
  ASSERT_TRUE(r.renders.has_value());
  EXPECT_EQ(r.renders->frames.size(), 3u);
  for (const fs::path& f : {rq.ply, rq.baked, rq.renders})
    EXPECT_NE(job.status().find(f.string()), std::string::npos) << job.status();
  EXPECT_EQ(job.runs_ended(), 1u);
}

TEST(StudioExportJob, TheBakedModelAlsoInTheStandardFormats) {
  const fs::path run = tiny_intrinsic_run();
  const fs::path out = test::scratch_dir("studio_export_formats");
  ExportRequest rq;
  rq.run_dir = run;
  rq.baked = out / "baked.ply";
  rq.baked_iterations = 2;
  rq.baked_formats = {SplatFormat::Spz, SplatFormat::CompressedPly, SplatFormat::Antimatter, SplatFormat::Glb};
  rq.device = DeviceChoice::CPU;
  ExportJob job;
  job.start(rq);
  ASSERT_EQ(job.wait(std::chrono::seconds(120)), JobState::Done) << job.status();
  const GaussianPly baked = read_ply(rq.baked);
  for (const char* name : {"baked.spz", "baked.compressed.ply", "baked.splat", "baked.glb"}) {
    const GaussianPly g = read_gaussians(out / name);
    EXPECT_EQ(g.count, baked.count) << name;
    EXPECT_LE(compare_models(baked, g, match_by_position(baked, g)).position.max, 0.01) << name;
  }
  const ExportResult r = job.result();
  ASSERT_EQ(r.written.size(), 6u);  // baked ply, its json, the four formats
  EXPECT_EQ(r.written[2], out / "baked.spz");
  EXPECT_NE(r.summary.find("Niantic SPZ"), std::string::npos) << r.summary;
  EXPECT_TRUE(temp_files(out).empty());

  // The formats hold the baked model: without it the request is refused.
  ExportRequest alone = rq;
  alone.baked.clear();
  alone.ply = out / "m.ply";
  EXPECT_THROW(check_export_request(alone), Error);
  EXPECT_EQ(baked_format_path("x/baked.ply", SplatFormat::CompressedPly), fs::path("x/baked.compressed.ply"));
}

TEST(StudioExportJob, AnUnwritablePathFailsBeforeAnyWork) {
  const fs::path run = tiny_intrinsic_run();
  const fs::path out = test::scratch_dir("studio_export_unwritable");
  std::ofstream(out / "blocker.txt") << "a file, not a folder";
  ExportRequest rq;
  rq.run_dir = run;
  rq.ply = out / "model.ply";
  rq.baked = out / "blocker.txt" / "baked.ply";
  rq.device = DeviceChoice::CPU;
  ExportJob job;
  job.start(rq);
  ASSERT_EQ(job.wait(std::chrono::seconds(60)), JobState::Error);
  const std::string s = job.status();
  EXPECT_NE(s.find("baked PLY: "), std::string::npos) << s;
  EXPECT_NE(s.find((out / "blocker.txt" / "baked.ply").string()), std::string::npos) << s;
  EXPECT_NE(s.find("is not a folder"), std::string::npos) << s;
  EXPECT_FALSE(fs::exists(rq.ply));  // the checks run before the first part
  EXPECT_TRUE(job.result().written.empty());

  // Bad requests are refused at once.
  ExportRequest none;
  none.run_dir = run;
  EXPECT_THROW(job.start(none), Error);
  ExportRequest same = none;
  same.ply = same.baked = out / "x.ply";
  EXPECT_THROW(job.start(same), Error);
  // A folder that is not a run fails with the run's problem.
  ExportRequest not_run;
  not_run.run_dir = out;
  not_run.ply = out / "y.ply";
  not_run.device = DeviceChoice::CPU;
  job.start(not_run);
  ASSERT_EQ(job.wait(std::chrono::seconds(60)), JobState::Error);
  EXPECT_NE(job.status().find("load the run: "), std::string::npos) << job.status();
  EXPECT_NE(job.status().find(out.string()), std::string::npos) << job.status();
  EXPECT_FALSE(fs::exists(not_run.ply));
}

TEST(StudioExportJob, CancelWritesNothingFinishEarlyWritesTheModelSoFar) {
  const fs::path run = tiny_intrinsic_run();
  const fs::path out = test::scratch_dir("studio_export_cancel");
  ExportRequest rq;
  rq.run_dir = run;
  rq.baked = out / "baked.ply";
  rq.baked_iterations = 1000000;
  rq.device = DeviceChoice::CPU;
  auto wait_distilling = [](const ExportJob& job) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(300);  // generous: CI machines may be loaded
    while (!job.distilling() && job.active() && std::chrono::steady_clock::now() < end)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return job.distilling();
  };
  ExportJob job;
  job.start(rq);
  ASSERT_TRUE(wait_distilling(job)) << job.status();
  job.cancel();
  ASSERT_EQ(job.wait(std::chrono::seconds(30)), JobState::Cancelled) << job.status();
  EXPECT_NE(job.status().find("cancelled during baked PLY; nothing was written"), std::string::npos) << job.status();
  EXPECT_FALSE(fs::exists(rq.baked));
  EXPECT_FALSE(fs::exists(baked_json_path(rq.baked)));
  EXPECT_TRUE(temp_files(out).empty());

  job.start(rq);
  ASSERT_TRUE(wait_distilling(job)) << job.status();
  job.finish_early();
  ASSERT_EQ(job.wait(std::chrono::seconds(60)), JobState::Done) << job.status();
  EXPECT_EQ(read_ply(rq.baked).count, load_run_model(run, Device::CPU).count());
  const nlohmann::json j = read_json(baked_json_path(rq.baked));
  EXPECT_EQ(j["stopped"], true);
  EXPECT_LT(j["iterations"].get<int>(), 1000000);
}

TEST(StudioExportAppState, TheScriptPressesTheDialogsButton) {
  const fs::path run = tiny_intrinsic_run();
  const fs::path out = test::scratch_dir("studio_export_app_state");
  StudioSettings settings;
  settings.train_device = "cpu";
  AppState st(settings);
  FakeHost host(st);
  EXPECT_THROW(st.start_export(), Error);  // nothing open
  ASSERT_EQ(run_script(st, host, "open " + run.string() + "\n"), "");
  ASSERT_EQ(st.current_run(), run);
  EXPECT_TRUE(st.removal_result().empty());
  EXPECT_EQ(st.export_source(), run);

  // The dialog's remembered relative paths lie inside the exported run folder; absolute ones stay.
  settings.export_ply = true;
  settings.export_baked = true;
  settings.export_renders = false;
  settings.export_ply_path = "export/model.ply";
  settings.export_baked_path = (out / "b.ply").string();
  const ExportRequest r = st.export_request();
  EXPECT_EQ(r.run_dir, run);
  EXPECT_EQ(r.ply, run / "export" / "model.ply");
  EXPECT_EQ(r.baked, out / "b.ply");
  EXPECT_TRUE(r.renders.empty());
  EXPECT_TRUE(r.baked_formats.empty());
  settings.export_baked_spz = true;
  EXPECT_EQ(st.export_request().baked_formats, std::vector<SplatFormat>{SplatFormat::Spz});
  settings.export_baked_spz = false;
  settings.export_ply_path.clear();
  EXPECT_THROW(st.export_request(), Error);  // chosen without a path
  EXPECT_NE(run_script(st, host, "export\n")
                .find("t.txt:1: export: export: the intrinsic PLY is chosen but its path is empty"),
            std::string::npos);

  // `export` alone presses the button with the choices as they stand.
  settings.export_ply_path = "export/model.ply";
  settings.export_baked = false;
  ASSERT_EQ(run_script(st, host, "export\n"), "");
  EXPECT_EQ(read_ply(run / "export" / "model.ply").count, load_run_model(run, Device::CPU).count());

  // Script lines set the dialog's choices to their one part and press Export.
  ASSERT_EQ(
      run_script(st, host,
                 "export ply " + (out / "m.ply").string() + "\nexport renders " + (out / "r").string() + " test 2\n"),
      "");
  EXPECT_TRUE(settings.export_renders && !settings.export_ply && !settings.export_baked);
  EXPECT_EQ(settings.export_renders_dir, (out / "r").string());
  EXPECT_EQ(settings.export_frames, 2);
  EXPECT_EQ(read_ply(out / "m.ply").count, load_run_model(run, Device::CPU).count());
  EXPECT_TRUE(fs::exists(out / "r" / "contact_sheet.png"));
  EXPECT_NE(st.last_message().find("export done: exported " + (out / "r").string()), std::string::npos)
      << st.last_message();

  // A failing export is reported (status bar message, the script's expectation), and the editor goes on.
  std::ofstream(out / "blocker.txt") << "x";
  const std::string bad = (out / "blocker.txt" / "m.ply").string();
  ASSERT_EQ(run_script(st, host, "export_start ply " + bad + "\nexpect_export_error is not a folder\n"), "");
  EXPECT_TRUE(st.last_message_is_error());
  EXPECT_NE(st.last_message().find("export error: intrinsic PLY: " + bad), std::string::npos) << st.last_message();
  const std::string e1 = run_script(st, host, "export ply " + bad + "\n");
  EXPECT_NE(e1.find("t.txt:1: export: the export ended error (expected done): intrinsic PLY: " + bad),
            std::string::npos)
      << e1;
  const std::string e2 =
      run_script(st, host, "export_start ply " + (out / "m2.ply").string() + "\nexpect_export_error x\n");
  EXPECT_NE(e2.find("t.txt:2: expect_export_error: the export ended done (expected error)"), std::string::npos) << e2;
  EXPECT_NE(run_script(st, host, "export_cancel\n").find("no export is running"), std::string::npos);
  EXPECT_NE(run_script(st, host, "export_from removal\n").find("no cleaned scene"), std::string::npos);
}
