#pragma once
// A static 3D k-d tree over points for k-nearest-neighbour queries (outlier statistics, the selection
// graph). Built once by median splits on the axis of largest extent; queries are exact and deterministic:
// neighbours come sorted by (distance, index), so equal distances never reorder between runs.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace goris {

struct Neighbor {
  std::uint32_t index;  // into the points the tree was built over
  float dist2;          // squared Euclidean distance
};

class PointKdTree {
 public:
  PointKdTree() = default;
  explicit PointKdTree(std::vector<glm::vec3> points);

  std::size_t size() const { return points_.size(); }
  const glm::vec3& point(std::size_t i) const { return points_[i]; }
  // The point indices in the tree's (spatially coherent) order: querying all points in this order keeps
  // consecutive queries on nearby nodes, which is several times faster than index order on large sets.
  const std::vector<std::uint32_t>& spatial_order() const { return order_; }

  // The k nearest points to q, nearest first (fewer when the tree is smaller), leaving out index `skip`
  // (pass the query's own index to exclude it; any value >= size() excludes nothing). `out` is overwritten.
  void knn(const glm::vec3& q, int k, std::vector<Neighbor>& out, std::size_t skip = SIZE_MAX) const;

 private:
  void build(std::uint32_t lo, std::uint32_t hi);
  void search(std::uint32_t lo, std::uint32_t hi, const glm::vec3& q, int k, std::size_t skip,
              std::vector<Neighbor>& best) const;

  std::vector<glm::vec3> points_;
  std::vector<std::uint32_t> order_;  // point indices, arranged as an implicit tree over [lo, hi) ranges
  std::vector<glm::vec3> sorted_;     // points_[order_[i]]: queries walk memory in tree order
  std::vector<std::uint8_t> axis_;    // split axis of the node whose median sits at that position of order_
};

}  // namespace goris
