// The one output-path check of every command: never into a data set, never over a run's inputs, no folders
// made beyond the last level, and a refused command leaves no empty folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/io/output_path.h"
#include "tests/support/test_support.h"
#include "train/run/run_output_guard.h"

namespace goris {
namespace {
namespace fs = std::filesystem;

void touch(const fs::path& p) { std::ofstream(p) << "x"; }

TEST(OutputPath, NothingIsWrittenInsideADataSet) {
  const fs::path dir = test::scratch_dir("output_path_dataset");
  const fs::path data = dir / "data";
  fs::create_directories(data / "test");
  touch(data / "transforms_train.json");  // a NeRF-synthetic data set, recognised without being named
  test::expect_error([&] { check_output_dir(data / "test"); }, "inside the data set " + data.string());
  test::expect_error([&] { check_output_dir(data); }, "inside the data set");
  test::expect_error([&] { check_output_file(data / "test" / "metrics.json"); }, "inside the data set");
  // Named in the guard (a data set given as its camera file's folder, say), also when not recognisable.
  const fs::path other = dir / "other";
  fs::create_directories(other);
  test::expect_error([&] { check_output_dir(other / "renders", OutputGuard{{other}, {}}); }, "inside the data set");
  check_output_dir(dir / "renders");  // beside the data set is fine
  EXPECT_TRUE(fs::is_directory(dir / "renders"));
}

TEST(OutputPath, ARunsInputsAreKept) {
  const fs::path run = test::scratch_dir("output_path_run");
  TrainConfig config;
  touch(run / "config.json");
  touch(run / "point_cloud.ply");
  fs::create_directories(run / "checkpoints");
  const OutputGuard guard = run_output_guard(run, config);
  test::expect_error([&] { check_output_file(run / "point_cloud.ply", guard); }, "would overwrite");
  test::expect_error([&] { check_output_file(run / "config.json", guard); }, (run / "config.json").string());
  test::expect_error([&] { check_output_dir(run / "checkpoints", guard); }, "would overwrite");
  test::expect_error([&] { check_output_file(run / "selection.json", guard); }, "would overwrite");
  check_output_file(run / "selection.json", run_output_guard(run, config, /*keep_selection=*/false));
  check_output_file(run / "metrics.json", guard);
  EXPECT_FALSE(fs::exists(run / "metrics.json"));  // checked, not written
}

TEST(OutputPath, NoFoldersBeyondTheLastLevel) {
  const fs::path dir = test::scratch_dir("output_path_parents");
  test::expect_error([&] { check_output_file(dir / "missing" / "x.ply"); }, "the folder " + (dir / "missing").string() + " does not exist");
  EXPECT_FALSE(fs::exists(dir / "missing"));
  test::expect_error([&] { check_output_dir(dir / "a" / "b"); }, "does not exist");
  EXPECT_FALSE(fs::exists(dir / "a"));
  check_output_dir(dir / "a");
  EXPECT_TRUE(fs::is_empty(dir / "a"));
}

TEST(OutputPath, RemoveIfLeftEmpty) {
  const fs::path dir = test::scratch_dir("output_path_left_empty");
  try {
    const RemoveIfLeftEmpty guard(dir / "refused");
    fs::create_directories(dir / "refused");
    throw std::runtime_error("refused");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(dir / "refused"));
  {
    const RemoveIfLeftEmpty guard(dir / "finished");
    fs::create_directories(dir / "finished");
  }
  EXPECT_TRUE(fs::exists(dir / "finished"));  // no exception: kept, even empty
  try {
    const RemoveIfLeftEmpty guard(dir / "written");
    fs::create_directories(dir / "written");
    touch(dir / "written" / "part");
    throw std::runtime_error("failed later");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(fs::exists(dir / "written" / "part"));  // what was written stays
}

}  // namespace
}  // namespace goris
