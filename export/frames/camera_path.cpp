#include "export/frames/camera_path.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/gtc/quaternion.hpp>

#include "core/scene/gaussian_init.h"
#include "core/util/error.h"

namespace goris {

namespace {

constexpr float kTwoPi = 6.283185307179586f;

glm::vec3 camera_up(const Camera& c) { return -glm::vec3(c.R[0][1], c.R[1][1], c.R[2][1]); }  // -(row 1 of R)

// A unit vector perpendicular to the unit vector n.
glm::vec3 any_perpendicular(const glm::vec3& n) {
  const glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(n, a));
}

Camera with_pose(const Camera& intrinsics, const glm::mat3& R, const glm::vec3& eye) {
  Camera c = intrinsics;
  c.R = R;
  c.t = -(R * eye);
  return c;
}

}  // namespace

glm::vec3 cameras_up(const std::vector<Camera>& cameras) {
  glm::vec3 sum(0.0f);
  for (const Camera& c : cameras) sum += camera_up(c);
  const float len = glm::length(sum);
  return len > 1e-3f * float(std::max<size_t>(cameras.size(), 1)) ? sum / len : glm::vec3(0, 0, 1);
}

glm::vec3 cameras_focus(const std::vector<Camera>& cameras) {
  if (cameras.empty()) throw Error("camera path", "no cameras to find the scene centre from");
  const Box box = box_from_cameras(cameras);  // centred on the least-squares focus of the optical axes
  return 0.5f * (box.lo + box.hi);
}

OrbitPath orbit_from_cameras(const std::vector<Camera>& cameras) {
  OrbitPath p;
  p.center = cameras_focus(cameras);
  p.up = cameras_up(cameras);
  p.intrinsics = cameras.front();
  double height = 0, radius = 0;
  for (const Camera& c : cameras) {
    const glm::vec3 d = c.center() - p.center;
    const float h = glm::dot(d, p.up);
    height += h;
    radius += glm::length(d - h * p.up);
  }
  p.height = float(height / double(cameras.size()));
  p.radius = float(radius / double(cameras.size()));
  const glm::vec3 d0 = cameras.front().center() - p.center;
  const glm::vec3 horizontal = d0 - glm::dot(d0, p.up) * p.up;
  const float scale = std::max(glm::length(d0), 1e-12f);
  if (!(p.radius > 1e-4f * scale) || !std::isfinite(p.radius))
    throw Error("orbit path", "the cameras all sit on the vertical line through the scene centre: no circle to orbit on");
  p.start = glm::length(horizontal) > 1e-4f * scale ? glm::normalize(horizontal) : any_perpendicular(p.up);
  return p;
}

glm::vec3 orbit_eye(const OrbitPath& path, int k, int n) {
  const float a = kTwoPi * float(k) / float(n);
  const glm::vec3 side = glm::cross(path.up, path.start);  // 90 degrees counter-clockwise about up
  return path.center + path.height * path.up + path.radius * (std::cos(a) * path.start + std::sin(a) * side);
}

std::vector<Camera> orbit_cameras(const OrbitPath& path, int n) {
  if (n < 1) throw Error("orbit path", "the number of frames must be at least 1 (got " + std::to_string(n) + ")");
  std::vector<Camera> out;
  out.reserve(size_t(n));
  for (int k = 0; k < n; ++k) out.push_back(look_at_camera(path.intrinsics, orbit_eye(path, k, n), path.center, path.up));
  return out;
}

Camera look_at_camera(const Camera& intrinsics, const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
  const glm::vec3 z = glm::normalize(target - eye);
  glm::vec3 x = glm::cross(z, up);  // screen right = forward x up (OpenCV axes: x = y x z with y = -up)
  x = glm::length(x) > 1e-6f ? glm::normalize(x) : any_perpendicular(z);
  const glm::vec3 y = glm::cross(z, x);  // screen down
  glm::mat3 R;
  for (int c = 0; c < 3; ++c) {  // rows of R are the camera axes in world space (glm is column-major)
    R[c][0] = x[c];
    R[c][1] = y[c];
    R[c][2] = z[c];
  }
  return with_pose(intrinsics, R, eye);
}

std::vector<Camera> interpolated_cameras(const std::vector<Camera>& cameras, int count, std::uint64_t seed) {
  std::vector<Camera> out;
  const size_t n = cameras.size();
  if (n < 2 || count <= 0) return out;
  // Nearest cameras of each (by centre), at most 3.
  const size_t k = std::min<size_t>(3, n - 1);
  std::vector<std::vector<size_t>> near(n);
  for (size_t a = 0; a < n; ++a) {
    std::vector<std::pair<float, size_t>> d;
    for (size_t b = 0; b < n; ++b)
      if (b != a) d.emplace_back(glm::length(cameras[a].center() - cameras[b].center()), b);
    std::partial_sort(d.begin(), d.begin() + std::ptrdiff_t(k), d.end());
    for (size_t i = 0; i < k; ++i) near[a].push_back(d[i].second);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> frac(0.25f, 0.75f);
  out.reserve(size_t(count));
  for (int j = 0; j < count; ++j) {
    const Camera& a = cameras[size_t(j) % n];
    const Camera& b = cameras[near[size_t(j) % n][std::uniform_int_distribution<size_t>(0, k - 1)(rng)]];
    const float t = frac(rng);
    const glm::quat q = glm::slerp(glm::quat_cast(a.R), glm::quat_cast(b.R), t);
    out.push_back(with_pose(a, glm::mat3_cast(glm::normalize(q)), glm::mix(a.center(), b.center(), t)));
  }
  return out;
}

std::vector<size_t> evenly_spaced(size_t n, int k) {
  const size_t m = k <= 0 || size_t(k) >= n ? n : size_t(k);
  std::vector<size_t> idx(m);
  for (size_t i = 0; i < m; ++i) idx[i] = i * n / m;
  return idx;
}

}  // namespace goris
