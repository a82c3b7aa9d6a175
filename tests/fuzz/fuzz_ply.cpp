// libFuzzer target for the PLY reader: any bytes must either parse into a consistent GaussianPly or throw
// goris::Error; anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <cstdlib>

#include "core/io/ply.h"
#include "core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  goris::GaussianPly g;
  try {
    g = goris::parse_ply(data, size, "fuzz.ply");
  } catch (const goris::Error&) {
    return 0;
  }
  try {
    g.check_consistent("fuzz.ply");  // what the reader returns must be writable as it is
  } catch (const goris::Error&) {
    std::abort();
  }
  return 0;
}
