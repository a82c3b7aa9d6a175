#include "core/scene/plane_from_masks.h"

#include "core/scene/select_hull.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace goris {

glm::dvec3 mean_camera_up(const std::vector<Camera>& cameras) {
  // An upright camera's right axis is level, so world up is the direction most perpendicular to every
  // camera's right axis: the smallest eigenvector of sum r r^T. The mean of the cameras' up axes would lean
  // towards the scene when the cameras cover only a sector of directions (they look down at it). The mean
  // up gives the sign, and is the answer when the right axes do not span a plane (one direction only).
  glm::dvec3 mean(0.0);
  glm::dmat3 rr(0.0);
  for (const Camera& c : cameras) {
    mean -= glm::dvec3(c.R[0][1], c.R[1][1], c.R[2][1]);  // rows of R are the camera's axes in world space
    const glm::dvec3 r(c.R[0][0], c.R[1][0], c.R[2][0]);
    rr += glm::outerProduct(r, r);
  }
  if (!(glm::length(mean) > 1e-9)) return glm::dvec3(0.0);
  mean = glm::normalize(mean);
  glm::dvec3 values;
  glm::dmat3 vectors;
  symmetric_eigen(rr / double(cameras.size()), values, vectors);
  // values descending (select_hull.h): the last is the smallest; a plane spanned needs the middle one > 0.
  if (!(values[1] > 1e-3)) return mean;
  glm::dvec3 up = glm::normalize(vectors[2]);
  return glm::dot(up, mean) < 0 ? -up : up;
}

namespace {
struct Pair {
  int i, j;
};

bool glossy_at(const std::vector<float>& m, const Camera& c, glm::vec2 uv) {
  const int x = int(std::floor(uv.x)), y = int(std::floor(uv.y));
  return m[std::size_t(y) * c.width + x] > 0.5f;
}

// Mean IoU over the pairs of view i's mask and view j's mask carried into i by the plane n . x = h.
double score(const std::vector<Camera>& cams, const std::vector<const std::vector<float>*>& masks,
             const std::vector<Pair>& pairs, const glm::dvec3& n, double h, int step) {
  double sum = 0;
  int used = 0;
  for (const Pair& p : pairs) {
    const Camera &ci = cams[p.i], &cj = cams[p.j];
    const glm::dvec3 eye(ci.center());
    std::size_t both = 0, either = 0, samples = 0, mapped = 0;
    for (int y = step / 2; y < ci.height; y += step)
      for (int x = step / 2; x < ci.width; x += step) {
        ++samples;
        const glm::dvec3 d(ci.ray_direction(float(x) + 0.5f, float(y) + 0.5f));
        const double dn = glm::dot(d, n);
        if (std::abs(dn) < 1e-6) continue;
        const double t = (h - glm::dot(eye, n)) / dn;
        if (!(t > 0)) continue;
        const glm::vec3 cam_j = cj.to_camera(glm::vec3(eye + t * d));
        if (!(cam_j.z > 0)) continue;
        const glm::vec2 uv = cj.project_camera(cam_j);
        if (!(uv.x >= 0 && uv.y >= 0 && uv.x < float(cj.width) && uv.y < float(cj.height))) continue;
        ++mapped;
        const bool a = (*masks[p.i])[std::size_t(y) * ci.width + x] > 0.5f, b = glossy_at(*masks[p.j], cj, uv);
        both += a && b;
        either += a || b;
      }
    // A height at which the views barely overlap (a plane just below the cameras) scores nothing for the
    // pair: a few samples landing in one patch of the other view would agree by chance.
    ++used;
    if (either == 0 || mapped * 4 < samples) continue;
    sum += double(both) / double(either);
  }
  return used ? sum / used : 0.0;
}
}  // namespace

PlaneFromMasks plane_from_glossy_masks(const std::vector<Camera>& cameras,
                                       const std::vector<const std::vector<float>*>& masks,
                                       const PlaneFromMasksSettings& s,
                                       std::optional<PlaneHeights> heights) {
  PlaneFromMasks out;
  const glm::dvec3 up = mean_camera_up(cameras);
  if (glm::length(up) == 0 || masks.size() != cameras.size()) return out;
  std::vector<int> usable;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const std::vector<float>* m = masks[i];
    if (!m || m->size() != std::size_t(cameras[i].width) * cameras[i].height || cameras[i].has_distortion()) continue;
    const auto on = std::count_if(m->begin(), m->end(), [](float v) { return v > 0.5f; });
    if (double(on) >= s.min_share * double(m->size())) usable.push_back(int(i));
  }
  if (usable.size() < 2) return out;
  // Reference views spread over the usable ones, each with its nearest neighbours by camera direction.
  std::vector<Pair> pairs;
  const int refs = std::min<int>(s.views, int(usable.size()));
  for (int k = 0; k < refs; ++k) {
    const int i = usable[std::size_t(k) * usable.size() / std::size_t(refs)];
    std::vector<std::pair<double, int>> near;
    for (int j : usable)
      if (j != i) near.push_back({-glm::dot(cameras[i].forward(), cameras[j].forward()), j});
    std::sort(near.begin(), near.end());
    for (int k2 = 0; k2 < s.neighbours && k2 < int(near.size()); ++k2) pairs.push_back({i, near[std::size_t(k2)].second});
  }
  // Heights from well below the cameras to the lowest camera: the surface is seen from above.
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  glm::dvec3 centre(0.0);
  for (const Camera& c : cameras) {
    const double h = glm::dot(glm::dvec3(c.center()), up);
    lo = std::min(lo, h), hi = std::max(hi, h);
    centre += glm::dvec3(c.center());
  }
  centre /= double(cameras.size());
  double spread = 0;
  for (const Camera& c : cameras) spread = std::max(spread, glm::length(glm::dvec3(c.center()) - centre));
  const double top = heights ? heights->high : lo - 1e-3 * spread;
  const double bottom = heights ? heights->low : lo - 2.0 * spread;
  if (!(top > bottom)) return out;
  // Near-ties (within tie_iou) go to the level plane nearest the preferred height: a surface that fills
  // every view scores alike at many heights and tilts.
  const double prefer = heights && heights->preferred ? *heights->preferred : 0.0;
  double best_h = top, best = -1;
  glm::dvec3 best_n = up;
  auto cost = [&](const glm::dvec3& n, double h) { return std::abs(h - prefer) + (1.0 - glm::dot(n, up)) * spread; };
  auto search = [&](const glm::dvec3& n, double a, double b, int steps) {
    for (int k = 0; k <= steps; ++k) {
      const double h = a + (b - a) * double(k) / double(steps);
      const double sc = score(cameras, masks, pairs, n, h, s.step);
      const bool tie = heights && heights->preferred && std::abs(sc - best) <= s.tie_iou;
      if ((sc > best && !tie) || (tie && cost(n, h) < cost(best_n, best_h))) {
        best = std::max(best, sc), best_h = h, best_n = n;
      }
    }
  };
  search(up, bottom, top, s.coarse);
  const double cell = (top - bottom) / double(s.coarse);
  search(up, best_h - cell, best_h + cell, 16);
  // The surface need not be exactly level, nor the cameras exactly upright: tilts of the normal up to
  // max_tilt_deg, each with its best height near the level one's, then the height once more.
  const glm::dvec3 a = glm::normalize(glm::cross(up, std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 b = glm::cross(up, a);
  const double level_h = best_h, rad = 3.14159265358979323846 / 180.0;
  const int t = std::max(0, s.tilt_steps);
  for (int i = -t; i <= t; ++i)
    for (int j = -t; j <= t; ++j) {
      if (i == 0 && j == 0) continue;
      const double ti = std::tan(s.max_tilt_deg * rad * i / std::max(1, t)), tj = std::tan(s.max_tilt_deg * rad * j / std::max(1, t));
      search(glm::normalize(up + ti * a + tj * b), level_h - cell, level_h + cell, 8);
    }
  search(best_n, best_h - cell / 4, best_h + cell / 4, 16);
  out.iou = best;
  out.plane.normal = best_n;
  out.plane.offset = best_h;
  out.plane.tolerance = 0.01 * spread;
  out.plane.found = best >= s.min_iou;
  return out;
}

std::optional<PlaneHeights> target_rest_heights(const std::vector<Camera>& cameras,
                                                const std::vector<const std::vector<float>*>& masks,
                                                const std::vector<glm::vec3>& centres,
                                                const std::vector<std::uint8_t>& target) {
  const glm::dvec3 up = mean_camera_up(cameras);
  if (glm::length(up) == 0) return std::nullopt;
  std::vector<double> h;
  for (std::size_t g = 0; g < centres.size() && g < target.size(); ++g) {
    if (!target[g]) continue;
    int seen = 0, on_glossy = 0;
    for (std::size_t i = 0; i < cameras.size() && i < masks.size(); ++i) {
      const std::vector<float>* m = masks[i];
      if (!m || m->size() != std::size_t(cameras[i].width) * cameras[i].height) continue;
      const long long p = cameras[i].pixel_of(cameras[i].to_camera(centres[g]));
      if (p < 0) continue;
      ++seen;
      on_glossy += (*m)[std::size_t(p)] > 0.5f;
    }
    if (2 * on_glossy <= seen) h.push_back(glm::dot(up, glm::dvec3(centres[g])));
  }
  if (h.size() < 10) return std::nullopt;
  std::sort(h.begin(), h.end());
  const double bottom = h[h.size() / 20], span = std::max(h[h.size() * 19 / 20] - bottom, 1e-6);
  return PlaneHeights{bottom - 0.5 * span, bottom, bottom};
}

}  // namespace goris
