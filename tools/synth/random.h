#pragma once
// Seeded random numbers for scene presets. std::uniform_*_distribution is not specified bit-for-bit
// (libstdc++ and libc++ give different values), so the mapping from std::mt19937 (which is) is our own:
// the same seed gives the same scene on every platform.
#include <cstdint>
#include <random>
#include <vector>

namespace goris::synth {

class Rng {
 public:
  explicit Rng(uint32_t seed) : gen_(seed) {}
  // Uniform in [0, 1): 32 random bits scaled (exact in double).
  double unit() { return double(gen_()) * (1.0 / 4294967296.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  // Uniform integer in [lo, hi] (inclusive).
  int integer(int lo, int hi) { return lo + int(unit() * double(hi - lo + 1)); }
  bool chance(double p) { return unit() < p; }
  template <class T>
  const T& pick(const std::vector<T>& items) { return items[size_t(integer(0, int(items.size()) - 1))]; }

 private:
  std::mt19937 gen_;
};

}  // namespace goris::synth
