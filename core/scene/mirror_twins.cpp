#include "core/scene/mirror_twins.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "core/scene/select_hull.h"
#include "core/util/error.h"

namespace goris {

namespace {

double diagonal(const std::vector<glm::dvec3>& p) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
  return glm::length(hi - lo);
}

// Points within `tol` of the plane n . x = d; with normals, only those whose normal is within acos(min_cos)
// of n (either sign).
bool is_inlier(const std::vector<glm::dvec3>& p, const std::vector<glm::vec3>& normals, std::size_t i,
               const glm::dvec3& n, double d, double tol, double min_cos) {
  if (std::abs(glm::dot(n, p[i]) - d) > tol) return false;
  return normals.empty() || std::abs(glm::dot(glm::dvec3(normals[i]), n)) >= min_cos;
}

std::size_t count_inliers(const std::vector<glm::dvec3>& p, const std::vector<glm::vec3>& normals,
                          const glm::dvec3& n, double d, double tol, double min_cos) {
  std::size_t c = 0;
  for (std::size_t i = 0; i < p.size(); ++i) c += is_inlier(p, normals, i, n, d, tol, min_cos);
  return c;
}

}  // namespace

MirrorPlane fit_mirror_plane(const std::vector<glm::vec3>& centres, const MirrorSettings& s,
                             const std::vector<glm::vec3>& normals) {
  if (!normals.empty() && normals.size() != centres.size())
    throw Error("mirror plane", std::to_string(centres.size()) + " centres but " + std::to_string(normals.size()) +
                                    " normals");
  const double min_cos = std::cos(s.normal_tolerance_deg * 3.14159265358979323846 / 180.0);
  MirrorPlane plane;
  plane.glossy = centres.size();
  if (centres.size() < std::max<std::size_t>(s.min_glossy, 3)) return plane;
  const std::vector<glm::dvec3> p(centres.begin(), centres.end());
  plane.tolerance = s.tolerance_ratio * diagonal(p);
  if (!(plane.tolerance > 0)) return plane;

  // With normals only flat points can be inliers, so the fraction is of them: the glossy set also holds the
  // objects and the mirror world (nearly every Gaussian on steel_snowman), whose share varies from run to run.
  std::vector<std::size_t> flat;
  for (std::size_t i = 0; i < normals.size(); ++i)
    if (glm::length(normals[i]) > 0.5f) flat.push_back(i);
  const std::size_t candidates = normals.empty() ? p.size() : flat.size();
  if (candidates < 3) return plane;

  // RANSAC: the plane with the most centres within the tolerance. Hypotheses: three random candidates, and
  // with normals every other draw one flat centre along its own normal (three-point draws from the table
  // are rare when it holds a tenth of the candidates; one normal is noisy, which the refit below corrects).
  std::mt19937_64 rng(s.seed);
  std::uniform_int_distribution<std::size_t> pick(0, candidates - 1);
  auto point = [&](std::size_t k) { return normals.empty() ? k : flat[k]; };
  glm::dvec3 best_n(0.0);
  double best_d = 0;
  std::size_t best = 0;
  for (int it = 0; it < s.ransac_iterations; ++it) {
    glm::dvec3 n, a;
    if (!normals.empty() && it % 2 == 0) {
      const std::size_t i = point(pick(rng));
      a = p[i];
      n = glm::normalize(glm::dvec3(normals[i]));
    } else {
      a = p[point(pick(rng))];
      const glm::dvec3 b = p[point(pick(rng))], c = p[point(pick(rng))];
      const glm::dvec3 cr = glm::cross(b - a, c - a);
      const double len = glm::length(cr);
      if (len < 1e-12) continue;
      n = cr / len;
    }
    const double d = glm::dot(n, a);
    if (s.accept && !s.accept(n, d)) continue;
    const std::size_t k = count_inliers(p, normals, n, d, plane.tolerance, min_cos);
    if (k > best) best = k, best_n = n, best_d = d;
  }
  if (best < 3) return plane;

  // Least-squares refits of the inliers (the normal is the covariance's weakest direction), repeated while
  // the refitted plane gathers more inliers.
  for (int round = 0; round < 8; ++round) {
    std::vector<glm::dvec3> in;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (is_inlier(p, normals, i, best_n, best_d, plane.tolerance, min_cos)) in.push_back(p[i]);
    glm::dvec3 mean(0.0);
    for (const auto& q : in) mean += q;
    mean /= double(in.size());
    glm::dmat3 cov(0.0);
    for (const auto& q : in) cov += glm::outerProduct(q - mean, q - mean);
    glm::dvec3 values;
    glm::dmat3 vectors;
    symmetric_eigen(cov / double(in.size()), values, vectors);
    glm::dvec3 n = glm::normalize(vectors[2]);
    if (glm::dot(n, best_n) < 0) n = -n;
    const double d = glm::dot(n, mean);
    const std::size_t k = count_inliers(p, normals, n, d, plane.tolerance, min_cos);
    const bool better = k > best;
    if (round == 0 || better) plane.normal = n, plane.offset = d, plane.inliers = k;
    if (!better) break;
    best = k, best_n = n, best_d = d;
  }
  plane.candidates = candidates;
  plane.found = double(plane.inliers) >= s.min_inlier_fraction * double(candidates);
  return plane;
}

MirrorTwins select_mirror_twins(const std::vector<glm::vec3>& centres, const std::vector<std::uint8_t>& glossy,
                                const SelectionMask& target, const MirrorSettings& s,
                                const std::vector<glm::vec3>& normals) {
  if (glossy.size() != centres.size() || target.size() != centres.size() ||
      (!normals.empty() && normals.size() != centres.size()))
    throw Error("mirror twins", std::to_string(centres.size()) + " Gaussians, " + std::to_string(glossy.size()) +
                                    " glossy flags, " + std::to_string(target.size()) + " selection entries and " +
                                    std::to_string(normals.size()) + " normals");
  std::vector<glm::vec3> g, gn;
  for (std::size_t i = 0; i < centres.size(); ++i)
    if (glossy[i] && !target[i]) {
      g.push_back(centres[i]);
      if (!normals.empty()) gn.push_back(normals[i]);
    }
  const MirrorPlane plane = fit_mirror_plane(g, s, gn);
  if (!plane.found) {
    MirrorTwins none;
    none.plane = plane;
    none.twins.assign(centres.size(), 0);
    return none;
  }
  return twins_below_plane(centres, target, plane, s);
}

MirrorTwins twins_below_plane(const std::vector<glm::vec3>& centres, const SelectionMask& target,
                              const MirrorPlane& plane, const MirrorSettings& s) {
  if (target.size() != centres.size())
    throw Error("mirror twins", std::to_string(centres.size()) + " Gaussians and " + std::to_string(target.size()) +
                                    " selection entries");
  MirrorTwins out;
  out.twins.assign(centres.size(), 0);
  out.plane = plane;
  MirrorPlane& pl = out.plane;
  if (!pl.found) return out;

  // The target's side of the plane: where most of its centres are.
  double side = 0;
  for (std::size_t i = 0; i < centres.size(); ++i)
    if (target[i]) side += pl.signed_distance(glm::dvec3(centres[i])) > 0 ? 1 : -1;
  if (side < 0) pl.normal = -pl.normal, pl.offset = -pl.offset;

  std::vector<glm::dvec3> mirrored;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (!target[i]) continue;
    const glm::dvec3 c(centres[i]);
    const double h = pl.signed_distance(c);
    if (h > pl.tolerance) mirrored.push_back(c - 2.0 * h * pl.normal);
  }
  out.target_above = mirrored.size();
  if (mirrored.empty()) return out;
  glm::dvec3 mean(0.0);
  for (const auto& m : mirrored) mean += m;
  mean /= double(mirrored.size());
  std::vector<glm::vec3> grown;
  for (const auto& m : mirrored) grown.emplace_back(mean + s.hull_growth * (m - mean));
  const SelectionVolume volume = enclosing_volume(grown, 2.0 * pl.tolerance);
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (target[i] || pl.signed_distance(glm::dvec3(centres[i])) > -pl.tolerance) continue;
    if (volume.contains(centres[i])) out.twins[i] = 1, ++out.count;
  }
  out.candidates = out.count;
  if (double(out.count) < s.min_twin_share * double(mirrored.size())) {
    out.twins.assign(centres.size(), 0);
    out.count = 0;
  }
  return out;
}

}  // namespace goris
