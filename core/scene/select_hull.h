#pragma once
// The volume a selection is closed with (docs/design/maths.md, Stage 2: "plus those inside the hull of the
// selected centres"): the 3D convex hull of the selected centres (Quickhull, in double precision), or, when
// the centres are degenerate (fewer than 4, collinear or flat), an oriented bounding box around them padded
// by a thickness, because a hull of a flat set has no inside.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace goris {

// Intersection of half-spaces n . x <= d (the hull's facets, outward unit normals), with its bounding box.
struct ConvexHull {
  std::vector<glm::dvec4> planes;  // (n.x, n.y, n.z, d)
  std::vector<std::size_t> vertices;  // indices of the input points on the hull
  glm::dvec3 lo{0.0}, hi{0.0};
  double tolerance = 0.0;  // a point up to this far outside a facet still counts as inside
  bool contains(const glm::dvec3& p) const;
};

// Box around `center` with orthonormal axes (columns) and half extents along them.
struct OrientedBox {
  glm::dvec3 center{0.0};
  glm::dmat3 axes{1.0};
  glm::dvec3 half{0.0};
  bool contains(const glm::dvec3& p) const;
};

// Fewer than 4 points, or a set whose thickness (distance of the farthest point from the best plane
// through the first three extreme points) is below degenerate_ratio times its diameter, has no hull.
struct HullSettings {
  double degenerate_ratio = 1e-4;
  // Precision of the hull, relative to the set's diameter (bounding-box diagonal): points within this distance of the hull built
  // so far do not refine it, and contains() accepts points this far outside. 1e-3 keeps a hull of a
  // densely sampled round object at a few thousand facets instead of two per point.
  double tolerance_ratio = 1e-3;
};

// The hull of `points` to within HullSettings::tolerance_ratio, or false (out untouched) when the set is
// degenerate. A point the floating-point construction cannot add robustly (a non-simple horizon, only in
// near-coplanar configurations) is left out, making the hull slightly smaller there.
bool convex_hull(const std::vector<glm::dvec3>& points, ConvexHull& out, const HullSettings& settings = {});

// Principal axes of the points (eigenvectors of their covariance), extents from the points' projections,
// every half extent grown by `pad` (so that flat or single-point sets still enclose something).
OrientedBox oriented_box(const std::vector<glm::dvec3>& points, double pad);

// Symmetric 3x3 eigen-decomposition (cyclic Jacobi): eigenvalues descending, eigenvectors as columns.
void symmetric_eigen(const glm::dmat3& a, glm::dvec3& values, glm::dmat3& vectors);

struct SelectionVolume {
  enum class Kind { None, Hull, Box };
  Kind kind = Kind::None;
  ConvexHull hull;
  OrientedBox box;
  bool contains(const glm::vec3& p) const;
};

const char* volume_kind_name(SelectionVolume::Kind k);  // "none", "convex hull", "oriented box"

// The hull of the points, or (degenerate) their oriented box padded by box_pad; None for no points.
SelectionVolume enclosing_volume(const std::vector<glm::vec3>& points, double box_pad, const HullSettings& settings = {});

}  // namespace goris
