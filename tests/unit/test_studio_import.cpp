// The editor's capture import without a window: which paths the Open panel offers to import, where the
// data set goes by default, the script's import actions, and the import job (ui/document/capture_job.h) refusing an
// output inside the input and an unreadable video with nothing written, and cancelling a running COLMAP
// stage (a stand-in program that waits) with nothing written. Needs no COLMAP.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

#include "core/util/error.h"
#include "tests/support/capture_inputs.h"
#include "tests/support/test_support.h"
#include "ui/document/app_state.h"
#include "ui/document/capture_job.h"
#include "ui/script/script.h"
#include "ui/document/settings_store.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

// Every entry of `dir` (names), to check that nothing was added.
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.push_back(e.path().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST(StudioImport, OffersPhotoFoldersAndVideosNotDataSets) {
  const fs::path dir = test::scratch_dir("studio_import_offer");
  EXPECT_TRUE(is_capture_input(test::photo_folder(dir / "photos", 3)));
  EXPECT_FALSE(is_capture_input(test::resource_dir() / "default_scene"));  // a data set: opened
  std::ofstream(dir / "clip.mp4") << "x";  // by its extension; whether it decodes shows when importing
  EXPECT_TRUE(is_capture_input(dir / "clip.mp4"));
  std::ofstream(dir / "notes.txt") << "x";
  EXPECT_FALSE(is_capture_input(dir / "notes.txt"));
  fs::create_directories(dir / "empty");
  EXPECT_FALSE(is_capture_input(dir / "empty"));
  EXPECT_FALSE(is_capture_input(dir / "missing"));

  EXPECT_EQ(default_capture_output(dir / "photos"), dir / "photos_data");
  EXPECT_EQ(default_capture_output(dir / "photos/"), dir / "photos_data");
  fs::create_directories(dir / "photos_data");
  EXPECT_EQ(default_capture_output(dir / "photos"), dir / "photos_data_2");
  EXPECT_EQ(default_capture_output(dir / "clip.mp4"), dir / "clip_data");
}

TEST(StudioImport, ParsesTheScriptActions) {
  const auto a = parse_script("import_capture in/photos \"out data\" --max-images 12 --resolution 320 --matcher "
                              "sequential --masks m\nimport_capture_start v.mp4 o\nimport_cancel\nimport_wait\n"
                              "expect_import_error cannot read the video\n",
                              "s.txt");
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(a[0].kind, ScriptAction::Kind::ImportCapture);
  EXPECT_EQ(a[0].path, "in/photos");
  EXPECT_EQ(a[0].out, "out data");
  EXPECT_EQ(a[0].count, 12);
  EXPECT_EQ(a[0].width, 320);
  EXPECT_EQ(a[0].matcher, "sequential");
  EXPECT_EQ(a[0].masks, "m");
  EXPECT_EQ(a[1].kind, ScriptAction::Kind::ImportCaptureStart);
  EXPECT_EQ(a[1].matcher, "exhaustive");
  EXPECT_EQ(a[1].count, 0);
  EXPECT_EQ(a[2].kind, ScriptAction::Kind::ImportCancel);
  EXPECT_EQ(a[3].kind, ScriptAction::Kind::ImportWait);
  EXPECT_EQ(a[4].kind, ScriptAction::Kind::ExpectImportError);
  EXPECT_EQ(a[4].text, "cannot read the video");
  EXPECT_STREQ(action_name(ScriptAction::Kind::ImportCapture), "import_capture");

  auto error = [](const std::string& text) {
    try {
      parse_script(text, "s.txt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("import_capture in\n").find("s.txt:1: import_capture: expected 'import_capture INPUT OUT"),
            std::string::npos);
  EXPECT_NE(error("import_capture in out --matcher nearest\n").find("unknown matcher 'nearest'"), std::string::npos);
  EXPECT_NE(error("import_capture in out --max-images\n").find("'--max-images' needs a value"), std::string::npos);
  EXPECT_NE(error("import_capture in out --max-images x\n").find("'x' is not a whole number"), std::string::npos);
  EXPECT_NE(error("import_capture in out --fast 1\n").find("unknown option '--fast'"), std::string::npos);
  EXPECT_NE(error("import_cancel now\n").find("expected 'import_cancel'"), std::string::npos);
}

TEST(StudioImportJob, RefusalsWriteNothing) {
  const fs::path dir = test::scratch_dir("studio_import_refusals");
  const fs::path photos = test::photo_folder(dir / "photos", 3);
  std::ofstream(dir / "broken.mp4") << "not a video";
  const std::vector<std::string> before = entries(dir);

  CaptureJob job;
  capture::CaptureOptions o;
  o.input = photos;
  o.out = photos / "data";
  o.colmap = "/bin/true";  // gets past the COLMAP check wherever COLMAP is absent
  job.start(o);
  ASSERT_EQ(job.wait(std::chrono::seconds(60)), JobState::Error) << job.status();
  EXPECT_NE(job.status().find("lies inside the input folder"), std::string::npos) << job.status();

  o.input = dir / "broken.mp4";
  o.out = dir / "broken_data";
  job.start(o);
  ASSERT_EQ(job.wait(std::chrono::seconds(60)), JobState::Error) << job.status();
  EXPECT_NE(job.status().find("broken.mp4: cannot read the video"), std::string::npos) << job.status();
  EXPECT_FALSE(job.report());
  EXPECT_EQ(job.runs_ended(), 2u);
  EXPECT_EQ(entries(dir), before);
}

TEST(StudioImportJob, CancelStopsColmapAndWritesNothing) {
  const fs::path dir = test::scratch_dir("studio_import_cancel");
  const fs::path photos = test::photo_folder(dir / "photos", 4);
  // A stand-in COLMAP: reports one file of the feature stage, writes its process id, then waits.
  const fs::path fake = dir / "colmap";
  std::ofstream(fake) << "#!/bin/sh\necho $$ > '" << (dir / "pid").string()
                      << "'\necho 'Processed file [1/4]'\nexec sleep 120\n";
  fs::permissions(fake, fs::perms::owner_all);

  StudioSettings settings;
  AppState st(settings);
  capture::CaptureOptions o;
  o.input = photos;
  o.out = dir / "photos_data";
  o.colmap = fake;
  st.start_import(o);
  EXPECT_THROW(st.start_import(o), Error);  // one at a time
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  // The stand-in's line has come: it runs (the stage reports 0 of 0 before its program starts).
  auto waiting = [&] { return st.importer().progress().stages[1].done < 1 && st.importer().active(); };
  while (waiting() && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(st.importer().progress().current, 1) << st.importer().status();  // the features stage
  ASSERT_EQ(st.importer().progress().stages[1].done, 1) << st.importer().status();
  EXPECT_TRUE(st.importer().progress().stages[0].complete);
  st.importer().cancel();
  ASSERT_EQ(st.importer().wait(std::chrono::seconds(30)), JobState::Cancelled) << st.importer().status();
  EXPECT_NE(st.importer().status().find("nothing was written"), std::string::npos) << st.importer().status();
  EXPECT_FALSE(fs::exists(o.out));
  EXPECT_FALSE(fs::exists(dir / ".photos_data.capture-tmp"));
  int pid = 0;
  std::ifstream(dir / "pid") >> pid;
  ASSERT_GT(pid, 0);
  EXPECT_NE(::kill(pid, 0), 0) << "the COLMAP stand-in still runs";
  EXPECT_FALSE(st.import_reported());
  st.poll();
  EXPECT_TRUE(st.import_reported());
  EXPECT_NE(st.last_message().find("import cancelled"), std::string::npos) << st.last_message();
}
