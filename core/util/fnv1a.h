#pragma once
// 64-bit FNV-1a: the checksum of checkpoint files and the fingerprints (of a model, a selection, a data set's
// views, a suite scene's images) that run files and bench results record.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace goris {

// A 64-bit value as the 16 hex digits every fingerprint in the run files is written as.
inline std::string hex16(std::uint64_t v) {
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
  return s;
}

struct Fnv1a {
  std::uint64_t value = 1469598103934665603ull;
  void byte(std::uint8_t b) {
    value ^= b;
    value *= 1099511628211ull;
  }
  void bytes(const void* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) byte(static_cast<const std::uint8_t*>(p)[i]);
  }
  std::string hex() const { return hex16(value); }
};

inline std::uint64_t fnv1a(std::string_view bytes) {
  Fnv1a h;
  h.bytes(bytes.data(), bytes.size());
  return h.value;
}

}  // namespace goris
