// Quickhull in 3D (Barber, Dobkin, Huhdanpaa 1996): start from a tetrahedron of extreme points, give every
// point outside a facet to that facet, then repeatedly take a facet's farthest outside point (the eye),
// find the facets it sees (a connected region, by walking neighbours), replace them with a cone of new
// facets from the horizon to the eye and redistribute the orphaned outside points.
// Two thresholds: visibility uses the rounding level (the facets stay a convex polytope); only points
// farther out than the requested precision become vertices (few facets on densely sampled round objects).
// A final check moves points that stick out of a neighbouring facet by more than the precision back into
// the loop, so that contains() accepts every input point.
#include "core/scene/select_hull.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace goris {

namespace {

struct Face {
  int v[3] = {0, 0, 0};
  int nb[3] = {-1, -1, -1};  // the face across edge i = (v[i], v[(i + 1) % 3])
  glm::dvec3 n{0.0};
  double d = 0.0;
  std::vector<int> outside;
  bool alive = true;
  int stamp = -1;  // eye iteration in which `visible` was evaluated
  bool visible = false;
};

struct HorizonEdge {
  int a, b, face;  // edge a -> b of a visible face; `face` is the hidden neighbour across it
};

class Quickhull {
 public:
  // eps: rounding level, for the visibility of facets (so the hull stays convex); keep: how far outside
  // the hull built so far a point must lie to refine it (the hull's precision).
  Quickhull(const std::vector<glm::dvec3>& p, double eps, double keep) : p_(p), eps_(eps), keep_(keep) {}

  // False when no tetrahedron of the given thickness exists.
  bool run(double degenerate_ratio) {
    if (p_.size() < 4) return false;
    int tet[4];
    if (!initial_tetrahedron(degenerate_ratio, tet)) return false;
    static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
    for (const auto& f : kFaces) {
      Face face;
      face.v[0] = tet[f[0]];
      face.v[1] = tet[f[1]];
      face.v[2] = tet[f[2]];
      set_plane(face);
      if (dist(face, tet[f[3]]) > 0.0) {  // the fourth vertex must be behind every face
        std::swap(face.v[1], face.v[2]);
        set_plane(face);
      }
      faces_.push_back(face);
    }
    for (int f = 0; f < 4; ++f)
      for (int i = 0; i < 3; ++i) faces_[f].nb[i] = find_twin(f, i);

    std::vector<int> all;
    for (int i = 0; i < int(p_.size()); ++i)
      if (std::find(tet, tet + 4, i) == tet + 4) all.push_back(i);
    assign(all, {0, 1, 2, 3});

    std::vector<int> work{0, 1, 2, 3};
    for (;;) {
      expand(work);
      work = recheck();
      if (work.empty()) return true;
    }
  }

  void result(ConvexHull& h) const {
    h.planes.clear();
    std::vector<char> on(p_.size(), 0);
    for (const Face& f : faces_) {
      if (!f.alive) continue;
      h.planes.emplace_back(f.n, f.d);
      for (int k = 0; k < 3; ++k) on[f.v[k]] = 1;
    }
    h.vertices.clear();
    for (std::size_t i = 0; i < on.size(); ++i)
      if (on[i]) h.vertices.push_back(i);
  }

 private:
  double dist(const Face& f, int i) const { return glm::dot(f.n, p_[i]) - f.d; }

  // Quickhull's main loop over the faces in `work`: a face whose farthest outside point is more than keep_
  // away gets that point added as a vertex; faces with only nearer points stay (and keep their points, so
  // that recheck() can look at them again).
  void expand(std::vector<int> work) {
    while (!work.empty()) {
      const int f0 = work.back();
      work.pop_back();
      if (!faces_[f0].alive || faces_[f0].outside.empty()) continue;
      const int eye = farthest(faces_[f0]);
      if (!(dist(faces_[f0], eye) > keep_)) continue;
      ++stamp_;
      std::vector<int> visible;
      std::vector<HorizonEdge> horizon;
      find_visible(f0, eye, stamp_, visible, horizon);
      std::vector<int> cone;
      if (!add_cone(eye, horizon, cone)) {
        // A non-simple horizon (rounding in a near-coplanar configuration): leave this point out.
        auto& out = faces_[f0].outside;
        out.erase(std::find(out.begin(), out.end(), eye));
        work.push_back(f0);
        continue;
      }
      std::vector<int> orphans;
      for (int f : visible) {
        faces_[f].alive = false;
        for (int q : faces_[f].outside)
          if (q != eye) orphans.push_back(q);
        faces_[f].outside.clear();
        faces_[f].outside.shrink_to_fit();
      }
      assign(orphans, cone);
      for (int f : cone)
        if (!faces_[f].outside.empty()) work.push_back(f);
    }
  }

  // A point within keep_ of its own face's plane can still be farther outside another face (near a sharp
  // edge, e.g. the rim of a thin slab). Every point still held by a face is checked against the faces
  // around its own (all of them on small hulls; on large ones a walk to ever farther-outside neighbours,
  // which ends at the face it is farthest outside of, as the faces that see a point form a connected cap)
  // and moved there when that exceeds keep_; those faces need more work.
  std::vector<int> recheck() {
    std::vector<int> alive;
    for (int f = 0; f < int(faces_.size()); ++f)
      if (faces_[f].alive) alive.push_back(f);
    std::vector<std::pair<int, int>> held;  // (point, face)
    for (int f : alive)
      for (int q : faces_[f].outside) held.emplace_back(q, f);
    std::vector<int> best(held.size(), -1);
    const bool scan_all = alive.size() <= 256;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, held.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        const int q = held[k].first;
        int at = held[k].second;
        double bd = dist(faces_[at], q);
        if (scan_all) {
          for (int f : alive)
            if (dist(faces_[f], q) > bd) {
              bd = dist(faces_[f], q);
              at = f;
            }
        } else {
          for (bool moved = true; moved;) {
            moved = false;
            for (int i = 0; i < 3; ++i) {
              const int g = faces_[at].nb[i];
              const double d = dist(faces_[g], q);
              if (d > bd) {
                bd = d;
                at = g;
                moved = true;
              }
            }
          }
        }
        if (bd > keep_) best[k] = at;
      }
    });
    std::vector<int> work;
    for (std::size_t k = 0; k < held.size(); ++k) {
      if (best[k] < 0) continue;
      auto& from = faces_[held[k].second].outside;
      from.erase(std::find(from.begin(), from.end(), held[k].first));
      faces_[best[k]].outside.push_back(held[k].first);
      work.push_back(best[k]);
    }
    std::sort(work.begin(), work.end());
    work.erase(std::unique(work.begin(), work.end()), work.end());
    return work;
  }

  void set_plane(Face& f) const {
    const glm::dvec3 a = p_[f.v[0]], b = p_[f.v[1]], c = p_[f.v[2]];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    f.n = len > 0.0 ? n / len : glm::dvec3(0.0);  // a sliver facet separates nothing
    f.d = glm::dot(f.n, (a + b + c) / 3.0);
  }

  int find_twin(int f, int i) const {
    const int a = faces_[f].v[i], b = faces_[f].v[(i + 1) % 3];
    for (int g = 0; g < int(faces_.size()); ++g)
      for (int j = 0; j < 3; ++j)
        if (g != f && faces_[g].v[j] == b && faces_[g].v[(j + 1) % 3] == a) return g;
    return -1;
  }

  bool initial_tetrahedron(double ratio, int tet[4]) const {
    const int n = int(p_.size());
    int ext[6] = {0, 0, 0, 0, 0, 0};  // min x, max x, min y, ...
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        if (p_[i][a] < p_[ext[2 * a]][a]) ext[2 * a] = i;
        if (p_[i][a] > p_[ext[2 * a + 1]][a]) ext[2 * a + 1] = i;
      }
    double best = -1.0;
    for (int s = 0; s < 6; ++s)
      for (int t = s + 1; t < 6; ++t) {
        const double d = glm::length(p_[ext[s]] - p_[ext[t]]);
        if (d > best) {
          best = d;
          tet[0] = ext[s];
          tet[1] = ext[t];
        }
      }
    if (!(best > 0.0)) return false;  // every point is the same point
    const double tol = ratio * best;
    const glm::dvec3 a = p_[tet[0]], dir = (p_[tet[1]] - a) / best;
    best = -1.0;
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 r = p_[i] - a;
      const double d = glm::length(r - glm::dot(r, dir) * dir);
      if (d > best) {
        best = d;
        tet[2] = i;
      }
    }
    if (!(best > tol)) return false;  // collinear
    const glm::dvec3 normal = glm::normalize(glm::cross(p_[tet[1]] - a, p_[tet[2]] - a));
    best = -1.0;
    for (int i = 0; i < n; ++i) {
      const double d = std::abs(glm::dot(normal, p_[i] - a));
      if (d > best) {
        best = d;
        tet[3] = i;
      }
    }
    return best > tol;  // else flat
  }

  int farthest(const Face& f) const {
    int best = f.outside.front();
    double bd = dist(f, best);
    for (int q : f.outside) {
      const double d = dist(f, q);
      if (d > bd || (d == bd && q < best)) {
        bd = d;
        best = q;
      }
    }
    return best;
  }

  // Faces that see the eye, as a connected region around f0, and the edges on its border (walked with an
  // explicit stack: visible regions can hold thousands of faces).
  void find_visible(int f0, int eye, int stamp, std::vector<int>& visible, std::vector<HorizonEdge>& horizon) {
    faces_[f0].stamp = stamp;
    faces_[f0].visible = true;
    std::vector<int> stack{f0};
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      visible.push_back(f);
      for (int i = 0; i < 3; ++i) {
        const int g = faces_[f].nb[i];
        Face& fg = faces_[g];
        if (fg.stamp != stamp) {
          fg.stamp = stamp;
          fg.visible = dist(fg, eye) > eps_;
          if (fg.visible) stack.push_back(g);
        }
        if (!fg.visible) horizon.push_back(HorizonEdge{faces_[f].v[i], faces_[f].v[(i + 1) % 3], g});
      }
    }
  }

  // New faces (a, b, eye) over the horizon, linked to each other and to the hidden faces. False (nothing
  // changed) when the horizon is not one simple cycle.
  bool add_cone(int eye, const std::vector<HorizonEdge>& horizon, std::vector<int>& cone) {
    if (horizon.size() < 3) return false;
    std::unordered_map<int, int> by_start, by_end;  // horizon vertex -> horizon edge index
    for (int k = 0; k < int(horizon.size()); ++k) {
      if (!by_start.emplace(horizon[k].a, k).second) return false;
      if (!by_end.emplace(horizon[k].b, k).second) return false;
    }
    int k = 0;
    for (std::size_t steps = 0; steps < horizon.size(); ++steps) {
      auto it = by_start.find(horizon[k].b);
      if (it == by_start.end()) return false;
      k = it->second;
      if (k == 0 && steps + 1 < horizon.size()) return false;  // more than one cycle
    }
    if (k != 0) return false;

    const int first = int(faces_.size());
    for (const HorizonEdge& h : horizon) {
      Face f;
      f.v[0] = h.a;
      f.v[1] = h.b;
      f.v[2] = eye;
      set_plane(f);
      faces_.push_back(std::move(f));
    }
    for (int e = 0; e < int(horizon.size()); ++e) {
      const HorizonEdge& h = horizon[e];
      const int nf = first + e;
      cone.push_back(nf);
      faces_[nf].nb[0] = h.face;
      Face& hidden = faces_[h.face];
      for (int j = 0; j < 3; ++j)
        if (hidden.v[j] == h.b && hidden.v[(j + 1) % 3] == h.a) hidden.nb[j] = nf;
      faces_[nf].nb[1] = first + by_start.at(h.b);  // across b -> eye: the face whose horizon edge starts at b
      faces_[nf].nb[2] = first + by_end.at(h.a);    // across eye -> a: the face whose horizon edge ends at a
    }
    return true;
  }

  // Gives each point to the face it is farthest outside of; points inside all of them are dropped.
  void assign(const std::vector<int>& points, const std::vector<int>& faces) {
    for (int q : points) {
      int best = -1;
      double bd = eps_;
      for (int f : faces) {
        const double d = dist(faces_[f], q);
        if (d > bd) {
          bd = d;
          best = f;
        }
      }
      if (best >= 0) faces_[best].outside.push_back(q);
    }
  }

  const std::vector<glm::dvec3>& p_;
  double eps_, keep_;
  std::vector<Face> faces_;
  int stamp_ = 0;
};

}  // namespace

bool ConvexHull::contains(const glm::dvec3& p) const {
  for (int k = 0; k < 3; ++k)
    if (p[k] < lo[k] - tolerance || p[k] > hi[k] + tolerance) return false;
  for (const glm::dvec4& pl : planes)
    if (glm::dot(glm::dvec3(pl), p) - pl.w > tolerance) return false;
  return true;
}

bool OrientedBox::contains(const glm::dvec3& p) const {
  const glm::dvec3 local = glm::transpose(axes) * (p - center);
  return std::abs(local.x) <= half.x && std::abs(local.y) <= half.y && std::abs(local.z) <= half.z;
}

bool convex_hull(const std::vector<glm::dvec3>& points, ConvexHull& out, const HullSettings& settings) {
  if (points.size() < 4) return false;
  glm::dvec3 lo = points[0], hi = points[0];
  double mag = 0.0;
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    mag = std::max({mag, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  const double diameter = glm::length(hi - lo);
  // Points within `keep` of the hull built so far do not refine it: that is both the hull's precision and
  // the slack of its inside test, and it keeps the facet count (the cost of testing a million centres)
  // small. Visibility uses the rounding level, so the facets always form a convex polytope.
  // Gaussian centres are floats (rounding ~1e-7 of their magnitude): a precision finer than 1e-5 of the
  // coordinates would let rounding noise create sliver facets with meaningless normals.
  const double eps = 1e-9 * (mag + diameter) + 1e-300;
  const double keep = std::max(settings.tolerance_ratio * diameter, 1e-5 * (mag + diameter));
  Quickhull qh(points, eps, keep);
  if (!qh.run(settings.degenerate_ratio)) return false;
  qh.result(out);
  out.lo = lo;
  out.hi = hi;
  out.tolerance = keep;
  return true;
}

void symmetric_eigen(const glm::dmat3& m, glm::dvec3& values, glm::dmat3& vectors) {
  double a[3][3], v[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      a[r][c] = m[c][r];
      v[r][c] = r == c ? 1.0 : 0.0;
    }
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diag || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // Rotation that zeroes a[p][q] (Numerical Recipes' stable form).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int idx[3] = {0, 1, 2};
  std::sort(idx, idx + 3, [&](int x, int y) { return a[x][x] > a[y][y]; });
  for (int k = 0; k < 3; ++k) {
    values[k] = a[idx[k]][idx[k]];
    vectors[k] = glm::dvec3(v[0][idx[k]], v[1][idx[k]], v[2][idx[k]]);
  }
  // A right-handed frame, so the box's axes are a rotation.
  if (glm::dot(glm::cross(vectors[0], vectors[1]), vectors[2]) < 0.0) vectors[2] = -vectors[2];
}

OrientedBox oriented_box(const std::vector<glm::dvec3>& points, double pad) {
  OrientedBox box;
  if (points.empty()) return box;
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& p : points) mean += p;
  mean /= double(points.size());
  glm::dmat3 cov(0.0);
  for (const glm::dvec3& p : points) cov += glm::outerProduct(p - mean, p - mean);
  glm::dvec3 values;
  symmetric_eigen(cov / double(points.size()), values, box.axes);
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const glm::dvec3& p : points) {
    const glm::dvec3 local = glm::transpose(box.axes) * (p - mean);
    lo = glm::min(lo, local);
    hi = glm::max(hi, local);
  }
  box.center = mean + box.axes * (0.5 * (lo + hi));
  box.half = 0.5 * (hi - lo) + glm::dvec3(std::max(pad, 0.0));
  return box;
}

bool SelectionVolume::contains(const glm::vec3& p) const {
  switch (kind) {
    case Kind::Hull: return hull.contains(glm::dvec3(p));
    case Kind::Box: return box.contains(glm::dvec3(p));
    case Kind::None: break;
  }
  return false;
}

const char* volume_kind_name(SelectionVolume::Kind k) {
  switch (k) {
    case SelectionVolume::Kind::Hull: return "convex hull";
    case SelectionVolume::Kind::Box: return "oriented box";
    case SelectionVolume::Kind::None: break;
  }
  return "none";
}

SelectionVolume enclosing_volume(const std::vector<glm::vec3>& points, double box_pad, const HullSettings& settings) {
  SelectionVolume v;
  if (points.empty()) return v;
  std::vector<glm::dvec3> p(points.begin(), points.end());
  if (convex_hull(p, v.hull, settings)) {
    v.kind = SelectionVolume::Kind::Hull;
  } else {
    v.kind = SelectionVolume::Kind::Box;
    v.box = oriented_box(p, box_pad);
  }
  return v;
}

}  // namespace goris
