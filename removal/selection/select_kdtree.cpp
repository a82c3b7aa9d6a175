#include "removal/selection/select_kdtree.h"

#include <algorithm>
#include <numeric>

namespace goris {

namespace {

constexpr std::uint32_t kLeaf = 8;  // ranges this small are scanned

bool closer(const Neighbor& a, const Neighbor& b) {
  return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
}

// Keeps `best` sorted and at most k long.
void offer(std::vector<Neighbor>& best, int k, Neighbor c) {
  if (int(best.size()) == k && !closer(c, best.back())) return;
  auto at = std::upper_bound(best.begin(), best.end(), c, closer);
  best.insert(at, c);
  if (int(best.size()) > k) best.pop_back();
}

}  // namespace

PointKdTree::PointKdTree(std::vector<glm::vec3> points) : points_(std::move(points)) {
  order_.resize(points_.size());
  std::iota(order_.begin(), order_.end(), 0u);
  axis_.assign(points_.size(), 0);
  build(0, std::uint32_t(points_.size()));
  sorted_.resize(points_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) sorted_[i] = points_[order_[i]];
}

void PointKdTree::build(std::uint32_t lo, std::uint32_t hi) {
  if (hi - lo <= kLeaf) return;
  glm::vec3 mn(points_[order_[lo]]), mx(mn);
  for (std::uint32_t i = lo + 1; i < hi; ++i) {
    mn = glm::min(mn, points_[order_[i]]);
    mx = glm::max(mx, points_[order_[i]]);
  }
  const glm::vec3 ext = mx - mn;
  const int a = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  const std::uint32_t mid = lo + (hi - lo) / 2;
  std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                   [&](std::uint32_t x, std::uint32_t y) {
                     const float px = points_[x][a], py = points_[y][a];
                     return px < py || (px == py && x < y);
                   });
  axis_[mid] = std::uint8_t(a);
  build(lo, mid);
  build(mid + 1, hi);
}

void PointKdTree::search(std::uint32_t lo, std::uint32_t hi, const glm::vec3& q, int k, std::size_t skip,
                         std::vector<Neighbor>& best) const {
  if (hi - lo <= kLeaf) {
    for (std::uint32_t i = lo; i < hi; ++i) {
      const std::uint32_t id = order_[i];
      if (id == skip) continue;
      const glm::vec3 d = sorted_[i] - q;
      offer(best, k, Neighbor{id, glm::dot(d, d)});
    }
    return;
  }
  const std::uint32_t mid = lo + (hi - lo) / 2;
  const std::uint32_t id = order_[mid];
  const int a = axis_[mid];
  if (id != skip) {
    const glm::vec3 d = sorted_[mid] - q;
    offer(best, k, Neighbor{id, glm::dot(d, d)});
  }
  const float diff = q[a] - sorted_[mid][a];
  const bool left_first = diff < 0.0f;
  if (left_first)
    search(lo, mid, q, k, skip, best);
  else
    search(mid + 1, hi, q, k, skip, best);
  // <=: a point on the far side at exactly the current worst distance may still win on its index.
  if (int(best.size()) < k || diff * diff <= best.back().dist2) {
    if (left_first)
      search(mid + 1, hi, q, k, skip, best);
    else
      search(lo, mid, q, k, skip, best);
  }
}

void PointKdTree::knn(const glm::vec3& q, int k, std::vector<Neighbor>& out, std::size_t skip) const {
  out.clear();
  if (k <= 0 || points_.empty()) return;
  out.reserve(std::size_t(k) + 1);
  search(0, std::uint32_t(points_.size()), q, k, skip, out);
}

}  // namespace goris
