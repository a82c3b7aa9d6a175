// libFuzzer target for the checkpoint reader (train/loop/checkpoint.cpp): the input is a checkpoint's body
// (after the magic), given the checksum it needs, so the fuzzer reaches the parser behind the checksum.
// Any body must load or throw goris::Error; anything else is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/util/error.h"
#include "core/util/fnv1a.h"
#include "train/loop/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("fuzz_checkpoint_" + std::to_string(getpid()) + ".ckpt");
  std::string bytes = "GORISCKP";
  bytes.append(reinterpret_cast<const char*>(data), size);
  const std::uint64_t sum = goris::fnv1a(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  try {
    const goris::Checkpoint ck = goris::read_checkpoint(path, goris::Device::CPU);
    if (ck.state.model.count() > size) std::abort();  // counts are bounded by the file
  } catch (const goris::Error&) {
  }
  return 0;
}
