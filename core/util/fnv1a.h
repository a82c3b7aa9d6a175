#pragma once
// 64-bit FNV-1a: the checksum of checkpoint files and the fingerprint of a model in selection files.
#include <cstdint>
#include <string_view>

namespace goris {

struct Fnv1a {
  std::uint64_t value = 1469598103934665603ull;
  void byte(std::uint8_t b) {
    value ^= b;
    value *= 1099511628211ull;
  }
};

inline std::uint64_t fnv1a(std::string_view bytes) {
  Fnv1a h;
  for (unsigned char c : bytes) h.byte(c);
  return h.value;
}

}  // namespace goris
