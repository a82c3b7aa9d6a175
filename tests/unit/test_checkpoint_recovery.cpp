// A run folder survives a kill during a checkpoint write: a truncated latest checkpoint is passed over for
// the previous intact one, and the temporary files of the killed write are removed on the next start.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/io/file_bytes.h"
#include "core/train/checkpoint.h"
#include "core/train/run_folder.h"
#include "core/train/trainer.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {
namespace fs = std::filesystem;

TrainerState small_state(int iteration) {
  GaussianModel m(Device::CPU);
  m.allocate(4);
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    for (size_t i = 0; i < t.value.size(); ++i) t.value[i] = 0.01f * float(i % 13);
  }
  for (int i = 0; i < 4; ++i) m.values(Param::Rotation)[i * 4] = 1.0f;
  TrainerState s = Trainer::initial_state(TrainConfig{}, std::move(m));
  s.stats.reset(s.model.count(), Device::CPU);
  s.iteration = iteration;
  return s;
}

TEST(CheckpointRecovery, TruncatedLatestFallsBackToThePreviousOne) {
  const fs::path run = test::scratch_dir("checkpoint_recovery_truncated");
  fs::create_directories(run / "checkpoints");
  write_checkpoint(checkpoint_path(run, 10), TrainConfig{}, small_state(10));
  write_checkpoint(checkpoint_path(run, 20), TrainConfig{}, small_state(20));
  ASSERT_EQ(latest_checkpoint(run), checkpoint_path(run, 20));
  fs::resize_file(checkpoint_path(run, 20), fs::file_size(checkpoint_path(run, 20)) / 2);  // killed mid-write
  ASSERT_EQ(latest_checkpoint(run), checkpoint_path(run, 10));
  EXPECT_EQ(read_checkpoint(*latest_checkpoint(run), Device::CPU).state.iteration, 10);
  EXPECT_EQ(load_run_model(run, Device::CPU).count(), 4u);
  // None intact: the latest is returned, and reading it says what is wrong.
  fs::resize_file(checkpoint_path(run, 10), 30);
  ASSERT_EQ(latest_checkpoint(run), checkpoint_path(run, 20));
  test::expect_error([&] { read_checkpoint(*latest_checkpoint(run), Device::CPU); }, "iter_00000020.ckpt");
}

TEST(CheckpointRecovery, TemporaryFilesOfADeadWriterAreRemoved) {
  const fs::path dir = test::scratch_dir("checkpoint_recovery_temp");
  // pid 0x7ffffffe: no such process; this process's own temporary files stay.
  const fs::path dead = dir / ".iter_00000020.tmp2147483646_0.ckpt";
  const fs::path mine = dir / (".iter_00000030.tmp" + std::to_string(::getpid()) + "_0.ckpt");
  const fs::path other = dir / ".hidden_notes";
  for (const fs::path& p : {dead, mine, other}) std::ofstream(p) << "x";
  remove_stale_temp_files(dir);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(mine));
  EXPECT_TRUE(fs::exists(other));
}

}  // namespace
}  // namespace goris
