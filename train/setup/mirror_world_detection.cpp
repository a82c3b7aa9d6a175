#include "train/setup/mirror_world_detection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <unordered_map>

#include "core/scene/cap_directions.h"
#include "core/util/median.h"

namespace goris {

namespace {

// The points in cubic cells of one size, to find a point near a position.
class PointGrid {
 public:
  PointGrid(const std::vector<glm::vec3>& pts, float cell) : pts_(pts), cell_(cell) {
    for (std::uint32_t i = 0; i < pts.size(); ++i) cells_[key(index(pts[i]))].push_back(i);
  }
  // Whether a point with height(x) > min_height lies within `radius` (<= the cell size) of q.
  template <class Height>
  bool near(const glm::vec3& q, float radius, const Height& height, float min_height) const {
    const glm::ivec3 c = index(q);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const std::uint32_t i : it->second)
            if (glm::length(pts_[i] - q) <= radius && height(pts_[i]) > min_height) return true;
        }
    return false;
  }

 private:
  glm::ivec3 index(const glm::vec3& x) const { return glm::ivec3(glm::floor(x / cell_)); }
  static std::uint64_t key(const glm::ivec3& c) {
    auto u = [](int v) { return std::uint64_t(std::uint32_t(v + (1 << 20))) & 0x1fffffu; };
    return u(c.x) | (u(c.y) << 21) | (u(c.z) << 42);
  }
  const std::vector<glm::vec3>& pts_;
  float cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

struct Candidate {
  glm::vec3 n{0.0f};
  float height = 0;
  std::size_t behind = 0, mirrored = 0, chance = 0;
  // The share of what lies behind the plane that mirrors what stands in front, above chance.
  double share() const { return behind ? (double(mirrored) - double(chance)) / double(behind) : -1.0; }
  // How much and how purely: the mirrored points above chance, times that share.
  double score() const { return behind ? share() * (double(mirrored) - double(chance)) : -1.0; }
};

}  // namespace

MirrorWorldPlane find_mirror_world_plane(const std::vector<glm::vec3>& all_points,
                                         const std::vector<glm::vec3>& cameras, const MirrorWorldPlaneSettings& s) {
  MirrorWorldPlane out;
  // At most max_points of them, picked by a fixed hash of their index (no stride that a regular pattern in
  // the input could alias with).
  std::vector<glm::vec3> pts;
  if (all_points.size() <= s.max_points) {
    pts = all_points;
  } else {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> order(all_points.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = {k * 2654435761u ^ (k >> 7) * 40503u, k};
    std::nth_element(order.begin(), order.begin() + long(s.max_points), order.end());
    for (std::size_t k = 0; k < s.max_points; ++k) pts.push_back(all_points[order[k].second]);
  }
  out.points = pts.size();
  if (pts.size() < 100 || cameras.empty()) {
    out.summary = "too few points for a mirror world";
    return out;
  }
  std::vector<float> xs, ys, zs;
  for (const glm::vec3& p : pts) xs.push_back(p.x), ys.push_back(p.y), zs.push_back(p.z);
  const glm::vec3 centre(median_of(xs), median_of(ys), median_of(zs));
  std::vector<float> cam_dist;
  glm::vec3 cam_mean(0.0f);
  for (const glm::vec3& c : cameras) cam_dist.push_back(glm::length(c - centre)), cam_mean += c;
  cam_mean /= float(cameras.size());
  const float scale = median_of(cam_dist);
  const glm::vec3 side = cam_mean - centre;
  if (!(scale > 0) || !(glm::length(side) > 0.05f * scale)) {
    out.summary = "the cameras surround the scene: no side to look from";
    return out;
  }
  const float depth = float(s.depth) * scale, front = float(s.front) * scale, match = float(s.match) * scale,
              shift = float(s.null_shift) * scale;
  const PointGrid grid(pts, match);

  // One plane: the points behind it, those whose reflection meets a point in front, and the same through
  // the plane raised by `shift` (the chance level: dense geometry near the plane matches something).
  auto evaluate = [&](const glm::vec3& n, float height) {
    Candidate c{n, height};
    auto h = [&](const glm::vec3& x) { return glm::dot(n, x); };
    for (const glm::vec3& x : pts) {
      const float hx = h(x);
      if (hx >= height - depth) continue;
      ++c.behind;
      c.mirrored += grid.near(x + 2.0f * (height - hx) * n, match, h, height + front);
      c.chance += grid.near(x + 2.0f * (height + shift - hx) * n, match, h, height + shift + front);
    }
    return c;
  };
  // Heights below every camera at quantiles of the points' heights along n.
  auto search = [&](const std::vector<glm::dvec3>& normals, Candidate& best) {
    for (const glm::dvec3& nd : normals) {
      const glm::vec3 n(nd);
      float lowest_camera = INFINITY;
      for (const glm::vec3& c : cameras) lowest_camera = std::min(lowest_camera, glm::dot(n, c));
      std::vector<float> hs;
      for (const glm::vec3& x : pts) hs.push_back(glm::dot(n, x));
      std::sort(hs.begin(), hs.end());
      for (int k = 0; k < s.offsets; ++k) {
        const double q = 0.05 + 0.65 * (s.offsets > 1 ? double(k) / (s.offsets - 1) : 0.0);
        const float height = hs[std::size_t(q * double(hs.size() - 1))];
        if (height + front >= lowest_camera) continue;
        const Candidate c = evaluate(n, height);
        if (double(c.mirrored) >= s.min_share * double(pts.size()) && c.score() > best.score()) best = c;
      }
    }
  };
  Candidate best;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(side));
  const double cap = s.cap_degrees * 3.14159265358979323846 / 180.0;
  search(cap_directions(axis, cap, s.normals), best);
  if (best.mirrored > 0) search(cap_directions(glm::dvec3(best.n), 0.1 * cap, s.normals), best);

  out.normal = best.n;
  out.height = best.height;
  out.behind = best.behind;
  out.mirrored = best.mirrored;
  out.chance = best.chance;
  const double share = double(best.mirrored) / double(pts.size());
  const double behind_share = best.behind ? double(best.mirrored) / double(best.behind) : 0.0;
  const double chance = best.mirrored ? double(best.chance) / double(best.mirrored) : 1.0;
  out.found = share >= s.min_share && behind_share >= s.min_behind_share && chance <= s.max_chance;
  char line[240];
  if (best.behind == 0) {
    std::snprintf(line, sizeof line,
                  "mirror world: none (no plane behind which %.0f %% of the %zu surface points mirror points in front)",
                  100.0 * s.min_share, pts.size());
    out.summary = line;
    return out;
  }
  std::snprintf(line, sizeof line,
                "mirror world: %.1f %% of %zu surface points mirror points in front of a plane (normal %.2f %.2f %.2f), "
                "%.0f %% of those behind it, chance %.0f %% -> %s",
                100.0 * share, pts.size(), best.n.x, best.n.y, best.n.z, 100.0 * behind_share, 100.0 * chance,
                out.found ? "found" : "none");
  out.summary = line;
  return out;
}

}  // namespace goris
