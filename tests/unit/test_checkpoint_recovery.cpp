// A run folder survives a kill during a checkpoint write: a truncated latest checkpoint (or a FIFO under a
// checkpoint's name) is passed over for the previous intact one, and the temporary files of the killed write
// are removed on the next start. When none is intact, the error names every file and how to start over.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <tuple>

#include "core/io/file_bytes.h"
#include "core/util/fnv1a.h"
#include "tests/support/test_support.h"
#include "train/loop/checkpoint.h"
#include "train/loop/hooks/hooks.h"
#include "train/loop/trainer.h"
#include "train/run/run_folder.h"

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
  // None intact: the error names each file with its problem and says how to start over.
  fs::resize_file(checkpoint_path(run, 10), 30);
  for (const char* part : {"iter_00000020.ckpt is truncated or corrupted", "iter_00000010.ckpt is truncated", "--restart"})
    test::expect_error([&] { latest_checkpoint(run); }, part);
  test::expect_error([&] { load_run_model(run, Device::CPU); }, "no intact checkpoint");
  test::expect_error([&] { read_checkpoint(checkpoint_path(run, 20), Device::CPU); }, "iter_00000020.ckpt");
}

// A FIFO under a checkpoint's name is refused by its type, never opened (that would wait for a writer
// forever): the latest intact checkpoint before it is used, and reading it directly names it as a FIFO.
TEST(CheckpointRecovery, FifoIsPassedOverWithoutOpeningIt) {
  const fs::path run = test::scratch_dir("checkpoint_recovery_fifo");
  fs::create_directories(run / "checkpoints");
  write_checkpoint(checkpoint_path(run, 100), TrainConfig{}, small_state(100));
  const fs::path fifo = checkpoint_path(run, 200);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_TRUE(has_checkpoint_files(run));
  ASSERT_EQ(latest_checkpoint(run), checkpoint_path(run, 100));
  EXPECT_EQ(load_run_model(run, Device::CPU).count(), 4u);
  test::expect_error([&] { read_checkpoint(fifo, Device::CPU); }, "iter_00000200.ckpt: is a FIFO (named pipe)");
  // The FIFO alone: no intact checkpoint, the FIFO named as such.
  fs::remove(checkpoint_path(run, 100));
  for (const char* part : {"iter_00000200.ckpt is a FIFO (named pipe), not a checkpoint file", "--restart"})
    test::expect_error([&] { latest_checkpoint(run); }, part);
  fs::remove(fifo);
  EXPECT_FALSE(has_checkpoint_files(run));
  EXPECT_FALSE(latest_checkpoint(run).has_value());
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


// Older format versions still load. A version-5 file turned into the version-4 layout (the adaptive
// densification record of a removed setting - an 8-byte check count, 20 bytes per check, a 4-byte stop
// iteration - inserted before the emit weights), version 3 (also without the emit-weight block: an 8-byte
// count and its floats) and version 2 (also without the record), the version field and checksum rewritten.
TEST(CheckpointFormat, OlderVersionsStillLoad) {
  const fs::path dir = test::scratch_dir("checkpoint_versions");
  TrainerState st = small_state(5);
  const std::vector<float> emit_weights{0.5f, 0.25f, 1.0f};
  const std::uint64_t emit_count = emit_weights.size();  // the emit-weights hook's state: a float block
  const std::string emit_state = std::string(reinterpret_cast<const char*>(&emit_count), sizeof emit_count) +
                                 std::string(reinterpret_cast<const char*>(emit_weights.data()), 4 * emit_count);
  st.hooks[EmitWeightsHook::kName] = emit_state;
  write_checkpoint(dir / "v5.ckpt", TrainConfig{}, st);
  std::ifstream in(dir / "v5.ckpt", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t version;
  std::memcpy(&version, bytes.data() + 8, 4);
  ASSERT_EQ(version, 5u);
  const std::size_t emit_block = emit_state.size();
  const std::string body = bytes.substr(0, bytes.size() - 8);
  const std::string head = body.substr(0, body.size() - emit_block), emit = body.substr(body.size() - emit_block);
  EXPECT_EQ(emit, emit_state) << "the hook's state is the file's emit-weight block as it is";
  auto pod = [](auto v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
  const std::string empty_record = pod(std::uint64_t(0)) + pod(std::int32_t(0));
  const std::string one_check = pod(std::uint64_t(1)) + pod(std::int32_t(4)) + pod(30.0) + pod(std::uint64_t(4)) +
                                pod(std::int32_t(0));
  auto older = [&](std::uint32_t v, std::string file, const char* name) {
    std::memcpy(file.data() + 8, &v, 4);
    file += pod(fnv1a(file));
    std::ofstream(dir / name, std::ios::binary) << file;
    return dir / name;
  };
  for (const auto& [v, file, name, emits] :
       {std::tuple{4u, head + empty_record + emit, "v4.ckpt", true}, std::tuple{4u, head + one_check + emit, "v4_check.ckpt", true},
        std::tuple{3u, head + empty_record, "v3.ckpt", false}, std::tuple{2u, head, "v2.ckpt", false}}) {
    SCOPED_TRACE(name);
    const Checkpoint ck = read_checkpoint(older(v, file, name), Device::CPU);
    EXPECT_EQ(ck.state.iteration, 5);
    EXPECT_EQ(ck.state.hooks, emits ? st.hooks : decltype(st.hooks){});
    EXPECT_EQ(ck.state.model.count(), 4u);
    EXPECT_EQ(ck.state.model.tensor(Param::Position).value.to_host(), st.model.tensor(Param::Position).value.to_host());
  }
  // A stop iteration past the checkpoint's own iteration is a damaged file, named in the error.
  const std::string late = pod(std::uint64_t(0)) + pod(std::int32_t(999));
  const fs::path bad = older(4u, head + late + emit, "bad.ckpt");
  test::expect_error([&] { read_checkpoint(bad, Device::CPU); }, "bad.ckpt");
}

}  // namespace
}  // namespace goris
