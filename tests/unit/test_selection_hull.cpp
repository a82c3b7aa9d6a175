// Geometry under target selection: k-d tree neighbours, the 3D convex hull and its inside test, the
// oriented-box fallback for degenerate sets, and the outlier rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/scene/select_hull.h"
#include "removal/selection/select_kdtree.h"
#include "removal/selection/select_outliers.h"

namespace goris {
namespace {

std::vector<glm::vec3> random_points(int n, unsigned seed, float lo = -1.0f, float hi = 1.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<glm::vec3> p(static_cast<std::size_t>(n));
  for (auto& x : p) x = glm::vec3(u(rng), u(rng), u(rng));
  return p;
}

TEST(SelectKdTree, MatchesBruteForceIncludingTiesAndSkip) {
  std::vector<glm::vec3> pts = random_points(2000, 1);
  // Exact duplicates and a regular lattice make equal distances: the order must still be (dist, index).
  for (int i = 0; i < 50; ++i) pts.push_back(pts[std::size_t(i)]);
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 5; ++y) pts.push_back(glm::vec3(2.0f + x * 0.25f, 2.0f + y * 0.25f, 0.0f));
  const PointKdTree tree(pts);
  std::vector<Neighbor> got;
  for (std::size_t q = 0; q < pts.size(); q += 7) {
    for (int k : {1, 5, 16}) {
      tree.knn(pts[q], k, got, q);
      std::vector<Neighbor> all;
      for (std::size_t i = 0; i < pts.size(); ++i)
        if (i != q) {
          const glm::vec3 d = pts[i] - pts[q];
          all.push_back(Neighbor{std::uint32_t(i), glm::dot(d, d)});
        }
      std::sort(all.begin(), all.end(), [](const Neighbor& a, const Neighbor& b) {
        return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
      });
      ASSERT_EQ(got.size(), std::size_t(k));
      for (int j = 0; j < k; ++j) {
        EXPECT_EQ(got[j].index, all[j].index) << "query " << q << " k " << k << " rank " << j;
        EXPECT_EQ(got[j].dist2, all[j].dist2);
      }
    }
  }
  tree.knn(glm::vec3(0.0f), 5000, got);  // more than there are: all of them
  EXPECT_EQ(got.size(), pts.size());
}

TEST(SelectHull, CubeCornersAndInteriorPoints) {
  std::vector<glm::dvec3> pts;
  for (int c = 0; c < 8; ++c) pts.emplace_back(c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.99, 0.99);
  for (int i = 0; i < 200; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  ConvexHull h;
  ASSERT_TRUE(convex_hull(pts, h));
  EXPECT_EQ(h.vertices.size(), 8u);  // only the corners are on the hull
  for (const auto& p : pts) EXPECT_TRUE(h.contains(p));
  EXPECT_TRUE(h.contains({0.0, 0.0, 0.0}));
  EXPECT_TRUE(h.contains({0.999, -0.999, 0.999}));
  EXPECT_FALSE(h.contains({1.01, 0.0, 0.0}));
  EXPECT_FALSE(h.contains({0.0, -1.01, 0.0}));
  EXPECT_FALSE(h.contains({0.9, 0.9, 1.05}));
}

TEST(SelectHull, PointsOnASphereMatchTheAnalyticInside) {
  // Every point is a hull vertex: the hardest case for Quickhull's bookkeeping.
  std::vector<glm::dvec3> pts;
  const int n = 3000;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
    pts.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  HullSettings exact;
  exact.tolerance_ratio = 0.0;  // down to the floor (1e-5 of the coordinates)
  ConvexHull h;
  ASSERT_TRUE(convex_hull(pts, h, exact));
  EXPECT_EQ(h.vertices.size(), std::size_t(n));
  EXPECT_EQ(h.planes.size(), std::size_t(2 * n - 4));  // a triangulated convex polyhedron
  for (const auto& p : pts) EXPECT_TRUE(h.contains(p));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 q(u(rng), u(rng), u(rng));
    const double r = glm::length(q);
    if (r < 0.995) EXPECT_TRUE(h.contains(q)) << r;  // the facets cut the sphere by < 0.1% of its radius
    if (r > 1.001) EXPECT_FALSE(h.contains(q)) << r;
  }
  // The default precision (1e-3 of the diameter) needs far fewer facets and still holds every point.
  ConvexHull coarse;
  ASSERT_TRUE(convex_hull(pts, coarse));
  EXPECT_LT(coarse.planes.size(), h.planes.size() / 2);
  EXPECT_NEAR(coarse.tolerance, 1e-3 * 2.0 * std::sqrt(3.0), 1e-5);  // of the bounding box's diagonal
  for (const auto& p : pts) EXPECT_TRUE(coarse.contains(p));
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 q(u(rng), u(rng), u(rng));
    const double r = glm::length(q);
    if (r < 0.99) EXPECT_TRUE(coarse.contains(q)) << r;
    if (r > 1.0 + 3.5e-3) EXPECT_FALSE(coarse.contains(q)) << r;
  }
}

TEST(SelectHull, ThinRoundSlabFarFromTheOriginHoldsEveryPoint) {
  // Float-rounded points on a flattened ellipsoid (radius 2, thickness 0.04) around (1000, -500, 20): the
  // rim's sharp edges are where a point within the precision of its own facet sticks out of the next one.
  for (const double ratio : {1e-3, 1e-6}) {
    std::mt19937 rng(7);
    std::normal_distribution<float> nd(0.0f, 1.0f);
    std::vector<glm::dvec3> pts;
    for (int i = 0; i < 20000; ++i) {
      glm::vec3 v = glm::normalize(glm::vec3(nd(rng), nd(rng), nd(rng)));
      v.z *= 0.01f;
      pts.push_back(glm::dvec3(v * 2.0f + glm::vec3(1000.0f, -500.0f, 20.0f)));
    }
    HullSettings hs;
    hs.tolerance_ratio = ratio;
    ConvexHull h;
    ASSERT_TRUE(convex_hull(pts, h, hs));
    int outside = 0;
    for (const auto& p : pts) outside += !h.contains(p);
    EXPECT_EQ(outside, 0) << ratio;
    EXPECT_FALSE(h.contains({1000.0, -500.0, 20.1}));
    EXPECT_TRUE(h.contains({1001.0, -500.0, 20.0}));
  }
}

TEST(SelectHull, LatticeWithManyCoplanarPointsAndNearDuplicates) {
  // Coplanar points on every face and float-rounded copies: the classic traps of Quickhull.
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 1000; ++i) pts.emplace_back(0.1 * (i % 10), 0.1 * (i / 10 % 10), 0.1 * (i / 100));
  for (int i = 0; i < 1000; i += 3) pts.push_back(glm::dvec3(glm::vec3(pts[std::size_t(i)]) * 1.0000001f));
  ConvexHull h;
  ASSERT_TRUE(convex_hull(pts, h));
  for (const auto& p : pts) EXPECT_TRUE(h.contains(p));
  EXPECT_LE(h.vertices.size(), 40u);  // the 8 corners (and rounding-level copies of them)
  EXPECT_TRUE(h.contains({0.45, 0.45, 0.45}));
  EXPECT_FALSE(h.contains({0.45, 0.45, 0.91}));
  EXPECT_FALSE(h.contains({-0.01, 0.45, 0.45}));
  // Many random clouds: every input point inside, every far point outside.
  for (unsigned seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    std::vector<glm::dvec3> cloud(static_cast<std::size_t>(200 + 50 * seed));
    for (auto& p : cloud) p = glm::dvec3(nd(rng), 0.3 * nd(rng), 2.0 * nd(rng));
    ConvexHull hc;
    ASSERT_TRUE(convex_hull(cloud, hc));
    for (const auto& p : cloud) ASSERT_TRUE(hc.contains(p)) << seed;
    EXPECT_FALSE(hc.contains({100.0, 0.0, 0.0}));
  }
}

TEST(SelectHull, DegenerateSetsHaveNoHull) {
  ConvexHull h;
  EXPECT_FALSE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, h));  // fewer than 4
  std::vector<glm::dvec3> flat, line, same(10, glm::dvec3(0.3, 0.2, 0.1));
  for (int i = 0; i < 50; ++i) {
    flat.emplace_back(std::cos(i * 0.7) * i, std::sin(i * 1.3) * 3.0, 2.0);  // the plane z = 2
    line.emplace_back(i * 0.1, i * 0.2, -i * 0.3);
  }
  EXPECT_FALSE(convex_hull(flat, h));
  EXPECT_FALSE(convex_hull(line, h));
  EXPECT_FALSE(convex_hull(same, h));
  // Thickness below degenerate_ratio x diameter also counts as flat; above it, a hull exists.
  flat.emplace_back(0.0, 0.0, 2.0 + 1e-6);
  EXPECT_FALSE(convex_hull(flat, h));
  flat.emplace_back(0.0, 0.0, 2.5);
  EXPECT_TRUE(convex_hull(flat, h));
}

TEST(SelectHull, SymmetricEigenReconstructs) {
  const glm::dmat3 a(4.0, 1.0, 0.5, 1.0, 3.0, -0.2, 0.5, -0.2, 1.0);
  glm::dvec3 w;
  glm::dmat3 v;
  symmetric_eigen(a, w, v);
  EXPECT_GE(w[0], w[1]);
  EXPECT_GE(w[1], w[2]);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 av = a * v[k];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(av[c], w[k] * v[k][c], 1e-12);
    EXPECT_NEAR(glm::length(v[k]), 1.0, 1e-12);
  }
  EXPECT_NEAR(glm::determinant(v), 1.0, 1e-12);
}

TEST(SelectHull, OrientedBoxOfAFlatTiltedSetIsPaddedAcrossIt) {
  // A flat rectangle 2 x 1 in a tilted plane.
  const glm::dvec3 e1 = glm::normalize(glm::dvec3(1, 1, 0)), e2 = glm::normalize(glm::dvec3(-1, 1, 1)),
                   n = glm::cross(e1, e2);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 5; ++j) pts.push_back(glm::dvec3(5, 0, 1) + (i * 0.2 - 1.0) * e1 + (j * 0.2 - 0.5) * e2);
  const OrientedBox box = oriented_box(pts, 0.05);
  EXPECT_NEAR(box.half[0], 1.05, 1e-9);
  EXPECT_NEAR(box.half[1], 0.55, 1e-9);
  EXPECT_NEAR(box.half[2], 0.05, 1e-9);
  const glm::dvec3 c(5, 0, 1);
  EXPECT_TRUE(box.contains(c + 0.04 * n));
  EXPECT_TRUE(box.contains(c + 1.0 * e1 - 0.5 * e2 - 0.04 * n));
  EXPECT_FALSE(box.contains(c + 0.06 * n));
  EXPECT_FALSE(box.contains(c + 1.1 * e1));

  const std::vector<glm::vec3> fp(pts.begin(), pts.end());
  const SelectionVolume v = enclosing_volume(fp, 0.05);
  EXPECT_EQ(v.kind, SelectionVolume::Kind::Box);
  EXPECT_TRUE(v.contains(glm::vec3(c + 0.04 * n)));
  EXPECT_EQ(enclosing_volume({}, 0.1).kind, SelectionVolume::Kind::None);
  EXPECT_EQ(enclosing_volume(random_points(20, 9), 0.1).kind, SelectionVolume::Kind::Hull);
  // One point: a cube of the padding around it.
  const SelectionVolume one = enclosing_volume({glm::vec3(1, 2, 3)}, 0.1);
  EXPECT_TRUE(one.contains(glm::vec3(1.09f, 2.0f, 2.91f)));
  EXPECT_FALSE(one.contains(glm::vec3(1.2f, 2.0f, 3.0f)));
}

TEST(SelectOutliers, IsolatedPointsAndSmallGroups) {
  std::vector<glm::vec3> pts = random_points(400, 11, -0.5f, 0.5f);  // the object
  pts.push_back(glm::vec3(4.0f, 0.0f, 0.0f));                        // a lone stray
  for (int i = 0; i < 12; ++i)                                        // a stray group: passes rule 1
    pts.push_back(glm::vec3(-4.0f, 0.0f, 0.0f) + 0.05f * glm::vec3(float(i % 3), float(i / 3 % 2), float(i / 6)));
  const OutlierResult r = find_outliers(pts);
  for (int i = 0; i < 400; ++i) EXPECT_EQ(r.outlier[std::size_t(i)], 0) << i;
  EXPECT_EQ(r.outlier[400], 1);
  for (int i = 401; i < 413; ++i) EXPECT_EQ(r.outlier[std::size_t(i)], 1) << i;
  EXPECT_GE(r.isolated, 1u);
  EXPECT_EQ(r.isolated + r.in_small_groups, 13u);

  OutlierSettings no_groups;
  no_groups.min_group_fraction = 0.0f;
  const OutlierResult r1 = find_outliers(pts, no_groups);
  EXPECT_EQ(r1.in_small_groups, 0u);
  EXPECT_EQ(r1.outlier[401], 0);  // the group's members are each other's neighbours

  EXPECT_EQ(find_outliers({{0, 0, 0}, {9, 9, 9}, {1, 1, 1}}).isolated, 0u);  // too few for statistics
  // Near-uniform sets (std tiny) have no outliers: not the seam of a ring that does not quite close, nor the
  // corners of a lattice (15% farther from their neighbours than the average point).
  std::vector<glm::vec3> ring, lattice;
  for (int i = 0; i < 100; ++i) ring.push_back(glm::vec3(std::cos(i * 0.0628f), std::sin(i * 0.0628f), 0.5f));
  for (int i = 0; i < 1000; ++i) lattice.push_back(0.1f * glm::vec3(float(i % 10), float(i / 10 % 10), float(i / 100)));
  const OutlierResult rr = find_outliers(ring), rl = find_outliers(lattice);
  EXPECT_EQ(std::count(rr.outlier.begin(), rr.outlier.end(), 1), 0);
  EXPECT_EQ(std::count(rl.outlier.begin(), rl.outlier.end(), 1), 0);
  // ... while the plain statistical rule (no floor) flags the lattice's corners.
  OutlierSettings plain;
  plain.min_ratio = 0.0f;
  plain.min_group_fraction = 0.0f;
  EXPECT_EQ(find_outliers(lattice, plain).outlier[0], 1);
}

}  // namespace
}  // namespace goris
