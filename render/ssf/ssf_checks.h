#pragma once
// Input checks shared by the glossy filter and the roughness net: sizes, devices and NaN/Inf, each failure a
// goris::Error naming the operation and the buffer.
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>

#include "core/compute/buffer.h"
#include "core/compute/finite_check.h"
#include "core/util/error.h"

namespace goris::ssf {

template <class T>
void check_buffer(const char* op, const char* name, const Buffer<T>& b, std::size_t expected, Device d) {
  if (b.size() != expected)
    throw Error(op, std::string(name) + " has " + std::to_string(b.size()) + " values, expected " +
                        std::to_string(expected));
  if (b.device() != d)
    throw Error(op, std::string(name) + " lives on " + device_name(b.device()) + ", expected " + device_name(d));
}

template <class T>
void check_finite(const char* op, const char* name, const Buffer<T>& b) {
  std::size_t bad = b.size();
  if constexpr (std::is_same_v<T, float>) {
    bad = first_non_finite(b.data(), b.size(), b.device());
  } else {
    if (b.device() != Device::CPU) throw Error(op, std::string(name) + ": double precision runs on the CPU only");
    for (std::size_t i = 0; i < b.size(); ++i)
      if (!std::isfinite(b[i])) {
        bad = i;
        break;
      }
  }
  if (bad != b.size()) throw Error(op, std::string(name) + " has a NaN or infinite value at index " + std::to_string(bad));
}

// Values must be >= 0 (weights). Checked where the buffer lives on the CPU; on CUDA the callers' own
// construction guarantees it (an extra transfer per call would cost more than the check is worth).
template <class T>
void check_non_negative(const char* op, const char* name, const Buffer<T>& b) {
  if (b.device() != Device::CPU) return;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b[i] < T(0)) throw Error(op, std::string(name) + " has a negative value at index " + std::to_string(i));
}

}  // namespace goris::ssf
