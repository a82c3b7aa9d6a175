// Bad input to the exports (export/run/run_export.h): unwritable outputs are refused before any work,
// a missing or broken run folder is an error naming the file, an unknown render path lists the known ones.
#include <fstream>
#include <string>

#include "core/util/error.h"
#include "export/run/run_export.h"
#include "tests/support/test_support.h"
#include "train/run/run_folder.h"

using namespace goris;
namespace fs = std::filesystem;

namespace {

// Runs f and returns the goris::Error's message ("" and a test failure when nothing is thrown).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a goris::Error";
  return "";
}

void touch(const fs::path& p) { std::ofstream(p) << "x"; }

}  // namespace

TEST(ExportBadInput, OutputPathsAreCheckedFirst) {
  const fs::path dir = test::scratch_dir("export_bad_outputs");
  const fs::path file = dir / "a_file";
  touch(file);
  // A folder where a file is wanted, a file where a folder is wanted, a folder under a file.
  EXPECT_NE(error_of([&] { check_output_file(dir); }).find("folder"), std::string::npos);
  std::string e = error_of([&] { check_output_dir(file); });
  EXPECT_NE(e.find(file.string()), std::string::npos) << e;
  EXPECT_NE(e.find("not a folder"), std::string::npos) << e;
  e = error_of([&] { check_output_file(file / "out.ply"); });
  EXPECT_NE(e.find((file / "out.ply").string()), std::string::npos) << e;
  e = error_of([&] { check_output_dir(file / "renders"); });
  EXPECT_NE(e.find("is not a folder"), std::string::npos) << e;
  // A file's folder must exist: no folders are made for it (a mistyped path is not created).
  e = error_of([&] { check_output_file(dir / "new" / "out.ply"); });
  EXPECT_NE(e.find("does not exist"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(dir / "new"));
  // Good paths: an output folder is created in an existing one, nothing is left behind.
  check_output_file(dir / "out.ply");
  EXPECT_FALSE(fs::exists(dir / "out.ply"));
  check_output_dir(dir / "renders");
  EXPECT_TRUE(fs::is_empty(dir / "renders"));
}

TEST(ExportBadInput, MissingOrBrokenRunFolder) {
  const fs::path dir = test::scratch_dir("export_bad_runs");
  std::string e = error_of([&] { RunExport(dir / "nope", Device::CPU); });
  EXPECT_NE(e.find("config.json"), std::string::npos) << e;
  // A run whose data set is gone.
  const fs::path run = dir / "run";
  fs::create_directories(run);
  TrainConfig c;
  c.input.data = (dir / "missing_dataset").string();
  write_run_config(run, c);
  e = error_of([&] { RunExport(run, Device::CPU); });
  EXPECT_NE(e.find("missing_dataset"), std::string::npos) << e;
  // A run with a data set but no model.
  c.input.data = (test::resource_dir() / "default_scene").string();
  write_run_config(run, c);
  e = error_of([&] { RunExport(run, Device::CPU); });
  EXPECT_NE(e.find("no trained model"), std::string::npos) << e;
}

TEST(ExportBadInput, RenderPathNames) {
  EXPECT_EQ(parse_render_path("test"), RenderPath::Test);
  EXPECT_EQ(parse_render_path("train"), RenderPath::Train);
  EXPECT_EQ(parse_render_path("orbit"), RenderPath::Orbit);
  const std::string e = error_of([] { parse_render_path("spiral"); });
  EXPECT_NE(e.find("test, train or orbit"), std::string::npos) << e;
  EXPECT_EQ(baked_json_path("/x/scene_baked.ply"), fs::path("/x/scene_baked.json"));
}
