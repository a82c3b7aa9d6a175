#include "tools/report/pareto.h"

#include <algorithm>
#include <cmath>

namespace goris {

std::vector<std::size_t> pareto_front(const std::vector<TimeQuality>& points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(points[i].time) && std::isfinite(points[i].quality)) order.push_back(i);
  // Fastest first; at equal time the best first; exact ties keep their input order.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].time != points[b].time) return points[a].time < points[b].time;
    return points[a].quality > points[b].quality;
  });
  std::vector<std::size_t> front;
  for (std::size_t i : order)
    // A point on the front must beat the quality of everything at least as fast.
    if (front.empty() || points[i].quality > points[front.back()].quality) front.push_back(i);
  return front;
}

}  // namespace goris
