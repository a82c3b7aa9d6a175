#pragma once
// The Pareto front of (time, quality) results: the points no other point beats on both axes at once,
// i.e. nothing is at least as fast and at least as good and strictly better on one of them.
#include <cstddef>
#include <vector>

namespace goris {

struct TimeQuality {
  double time = 0;     // minimised (seconds)
  double quality = 0;  // maximised (e.g. PSNR)
};

// Indices of the front, in increasing time (and so increasing quality). Points with a non-finite
// coordinate take no part. Among identical points only the first index is kept, so the front has one
// marker per step; of several points at the same time only the best quality survives.
std::vector<std::size_t> pareto_front(const std::vector<TimeQuality>& points);

}  // namespace goris
