#pragma once
// What every splat-format fuzz target checks (tests/fuzz/fuzz_spz.cpp, ...): a decoder either throws
// goris::Error or returns a model that is consistent and finite (what the PLY writer and the renderer accept).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/io/splat_formats.h"
#include "core/util/error.h"

namespace goris::fuzz {

using Decoder = GaussianPly (*)(const uint8_t*, size_t, const std::string&);

inline int check_decoder(Decoder decode, const uint8_t* data, size_t size, const char* name) {
  GaussianPly g;
  try {
    g = decode(data, size, name);
  } catch (const Error&) {
    return 0;
  }
  try {
    g.check_consistent(name);
  } catch (const Error&) {
    std::abort();
  }
  for (const std::vector<float>* v : {&g.positions, &g.f_dc, &g.f_rest, &g.opacity, &g.scales, &g.rotations})
    for (float f : *v)
      if (!std::isfinite(f)) std::abort();
  return 0;
}

}  // namespace goris::fuzz
