#pragma once
// The median every report and heuristic here uses: the upper middle element (v[n/2] of the sorted sample),
// 0 for an empty sample. O(n) by nth_element; the sample is taken by value (std::move it in to reuse it).
// Benchmark timings (core/compute/bench.h) average the two middle values instead.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace goris {

template <class T>
T median_of(std::vector<T> v) {
  if (v.empty()) return T(0);
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace goris
