// libFuzzer target for the PlayCanvas compressed PLY reader: any bytes must either decode into a consistent
// GaussianPly of finite values or throw goris::Error; anything else is a bug.
#include "tests/fuzz/fuzz_splat_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return goris::fuzz::check_decoder(goris::decode_compressed_ply, data, size, "fuzz.compressed.ply");
}
