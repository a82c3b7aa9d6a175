// libFuzzer target for the .npy reader (and the LLFF pose reader on what it returns). Any input must parse
// into an array whose size matches its shape, or throw goris::Error; anything else is a bug.
#include <cstdint>
#include <cstdlib>

#include "core/io/loaders/llff_poses.h"
#include "core/io/npy.h"
#include "core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  goris::NpyArray a;
  try {
    a = goris::parse_npy(data, size, "fuzz.npy");
  } catch (const goris::Error&) {
    return 0;
  }
  size_t count = 1;
  for (size_t d : a.shape) count *= d;
  if (count != a.data.size()) std::abort();
  try {
    goris::llff_poses_from_npy(a, "fuzz.npy");
  } catch (const goris::Error&) {
  }
  return 0;
}
