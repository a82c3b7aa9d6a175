// libFuzzer target for the SPZ reader: any bytes must either decode into a consistent GaussianPly of
// finite values or throw goris::Error; anything else (a crash, a sanitizer report, another exception) is a bug.
#include "tests/fuzz/fuzz_splat_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return goris::fuzz::check_decoder(goris::decode_spz, data, size, "fuzz.spz");
}
