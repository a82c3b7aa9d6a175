#include "removal/selection/select_outliers.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "removal/selection/select_kdtree.h"

namespace goris {

namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // deterministic roots
  }
};

}  // namespace

OutlierResult find_outliers(const std::vector<glm::vec3>& points, const OutlierSettings& s) {
  OutlierResult r;
  const std::size_t n = points.size();
  r.outlier.assign(n, 0);
  if (n < 4 || s.k < 1) return r;
  const int k = int(std::min<std::size_t>(std::size_t(s.k), n - 1));

  const PointKdTree tree(points);
  std::vector<std::uint32_t> nb(n * std::size_t(k));
  std::vector<float> nd(n * std::size_t(k));
  std::vector<double> mean_dist(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<Neighbor> found;
    for (std::size_t s = range.begin(); s != range.end(); ++s) {
      const std::size_t i = tree.spatial_order()[s];
      tree.knn(points[i], k, found, i);
      double sum = 0.0;
      for (int j = 0; j < k; ++j) {
        nb[i * k + j] = found[j].index;
        nd[i * k + j] = std::sqrt(found[j].dist2);
        sum += nd[i * k + j];
      }
      mean_dist[i] = sum / k;
    }
  });

  double mu = 0.0, var = 0.0;
  for (double m : mean_dist) mu += m;
  mu /= double(n);
  for (double m : mean_dist) var += (m - mu) * (m - mu);
  const double sigma = std::sqrt(var / double(n));
  const double bound = std::max(mu + double(s.std_ratio) * sigma, double(s.min_ratio) * mu);
  r.link_distance = float(bound);
  for (std::size_t i = 0; i < n; ++i)
    if (mean_dist[i] > bound) {
      r.outlier[i] = 1;
      ++r.isolated;
    }

  if (s.min_group_fraction <= 0.0f) return r;
  UnionFind uf(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (r.outlier[i]) continue;
    for (int j = 0; j < k; ++j) {
      const std::uint32_t o = nb[i * k + j];
      if (!r.outlier[o] && nd[i * k + j] <= bound) uf.unite(std::uint32_t(i), o);
    }
  }
  std::vector<std::size_t> size(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (!r.outlier[i]) ++size[uf.find(std::uint32_t(i))];
  const std::size_t largest = *std::max_element(size.begin(), size.end());
  for (std::size_t i = 0; i < n; ++i) {
    if (r.outlier[i]) continue;
    if (double(size[uf.find(std::uint32_t(i))]) < double(s.min_group_fraction) * double(largest)) {
      r.outlier[i] = 1;
      ++r.in_small_groups;
    }
  }
  return r;
}

}  // namespace goris
