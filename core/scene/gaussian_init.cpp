#include "core/scene/gaussian_init.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include <tbb/parallel_for.h>

#include "core/scene/gaussian_kernels.h"
#include "core/util/error.h"

namespace goris {

namespace {

// Implicit balanced k-d tree: the node of the index range [lo, hi) sits at mid = (lo + hi) / 2 of a
// permutation of the points, split on axis[mid]; left subtree [lo, mid), right (mid, hi).
class KdTree {
 public:
  explicit KdTree(const std::vector<glm::vec3>& pts) : pts_(pts), order_(pts.size()), axis_(pts.size()) {
    std::iota(order_.begin(), order_.end(), 0u);
    build(0, order_.size());
  }

  // The k smallest squared distances from point `self` to other points, ascending (fewer when there are
  // fewer other points).
  void nearest(uint32_t self, int k, std::vector<float>& best) const {
    best.clear();
    search(0, order_.size(), pts_[self], self, size_t(k), best);
  }

 private:
  void build(size_t lo, size_t hi) {
    if (hi - lo <= 1) {
      if (hi > lo) axis_[lo] = 0;
      return;
    }
    glm::vec3 mn(std::numeric_limits<float>::max()), mx(std::numeric_limits<float>::lowest());
    for (size_t i = lo; i < hi; ++i) {
      mn = glm::min(mn, pts_[order_[i]]);
      mx = glm::max(mx, pts_[order_[i]]);
    }
    const glm::vec3 ext = mx - mn;
    const int ax = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    const size_t mid = (lo + hi) / 2;
    std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                     [&](uint32_t a, uint32_t b) { return pts_[a][ax] < pts_[b][ax]; });
    axis_[mid] = uint8_t(ax);
    build(lo, mid);
    build(mid + 1, hi);
  }

  static void insert(std::vector<float>& best, size_t k, float d2) {
    if (best.size() == k && d2 >= best.back()) return;
    auto it = std::upper_bound(best.begin(), best.end(), d2);
    best.insert(it, d2);
    if (best.size() > k) best.pop_back();
  }

  void search(size_t lo, size_t hi, const glm::vec3& q, uint32_t self, size_t k, std::vector<float>& best) const {
    if (lo >= hi) return;
    const size_t mid = (lo + hi) / 2;
    const uint32_t id = order_[mid];
    if (id != self) {
      const glm::vec3 d = pts_[id] - q;
      insert(best, k, glm::dot(d, d));
    }
    const int ax = axis_[mid];
    const float diff = q[ax] - pts_[id][ax];
    const bool left_first = diff < 0;
    if (left_first) search(lo, mid, q, self, k, best);
    else search(mid + 1, hi, q, self, k, best);
    if (best.size() < k || diff * diff < best.back()) {
      if (left_first) search(mid + 1, hi, q, self, k, best);
      else search(lo, mid, q, self, k, best);
    }
  }

  const std::vector<glm::vec3>& pts_;
  std::vector<uint32_t> order_;
  std::vector<uint8_t> axis_;
};

}  // namespace

std::vector<float> knn_mean_distance(const std::vector<glm::vec3>& points, int k) {
  if (k < 1) throw Error("knn_mean_distance: k must be at least 1");
  std::vector<float> out(points.size(), 0.0f);
  if (points.size() < 2) return out;
  KdTree tree(points);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 512), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<float> best;
    best.reserve(size_t(k) + 1);
    for (size_t i = r.begin(); i != r.end(); ++i) {
      tree.nearest(uint32_t(i), k, best);
      double sum = 0;
      for (float d2 : best) sum += d2;
      out[i] = float(std::sqrt(sum / double(best.size())));
    }
  });
  return out;
}

GaussianModel init_from_points(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& colors,
                               Device device, const GaussianInit& init) {
  if (points.empty()) throw Error("initial points: none given");
  if (colors.size() != points.size()) throw Error("initial points: colour count differs from point count");
  const size_t n = points.size();
  const std::vector<float> dist = knn_mean_distance(points, 3);
  const float min_dist = std::sqrt(1e-7f);

  GaussianModel m(Device::CPU);
  m.allocate(n);
  m.sh_degree = 0;
  m.max_sh_degree = 3;
  float* pos = m.values(Param::Position);
  float* sc = m.values(Param::LogScale);
  float* rot = m.values(Param::Rotation);
  float* op = m.values(Param::OpacityLogit);
  float* sh = m.values(Param::Sh);
  float* ex = m.values(Param::ExtraLogit);
  const float ex_init[extra::kCount] = {init.diffuse, init.diffuse,   init.diffuse, init.fresnel, init.fresnel,
                                        init.fresnel, init.roughness, init.region,  init.label};
  const float op_logit = kernels::logit(init.opacity);
  for (size_t i = 0; i < n; ++i) {
    const float ls = std::log(std::max(dist[i], min_dist));
    for (int a = 0; a < 3; ++a) {
      pos[i * 3 + a] = points[i][a];
      sc[i * 3 + a] = ls;
    }
    rot[i * 4 + 0] = 1.0f;
    rot[i * 4 + 1] = rot[i * 4 + 2] = rot[i * 4 + 3] = 0.0f;
    op[i] = op_logit;
    float* s = sh + i * kMaxShCoeffs * 3;
    std::fill(s, s + kMaxShCoeffs * 3, 0.0f);
    for (int c = 0; c < 3; ++c) s[c] = kernels::sh_dc_from_colour(colors[i][c]);
    for (int c = 0; c < extra::kCount; ++c) ex[i * extra::kCount + c] = kernels::logit(ex_init[c]);
  }
  return device == Device::CPU ? std::move(m) : m.copy_to(device);
}

CameraFocus camera_focus(const std::vector<Camera>& cameras) {
  if (cameras.empty()) throw Error("camera focus: no cameras");
  // Least-squares point nearest to every optical axis: sum (I - d d^T) (x - c) = 0.
  glm::dmat3 A(0.0);
  glm::dvec3 b(0.0);
  for (const Camera& cam : cameras) {
    const glm::dvec3 c(cam.center()), d(glm::normalize(cam.forward()));
    const glm::dmat3 P = glm::dmat3(1.0) - glm::outerProduct(d, d);
    A += P;
    b += P * c;
  }
  glm::dvec3 center(0.0);
  if (std::abs(glm::determinant(A)) > 1e-9) {
    center = glm::inverse(A) * b;
  } else {  // parallel axes (e.g. one camera): a point in front of the mean camera
    for (const Camera& cam : cameras) center += glm::dvec3(cam.center()) + glm::dvec3(cam.forward());
    center /= double(cameras.size());
  }
  double dist = 0;
  for (const Camera& cam : cameras) dist += glm::length(glm::dvec3(cam.center()) - center);
  dist /= double(cameras.size());
  return {glm::vec3(center), float(dist)};
}

Box box_from_cameras(const std::vector<Camera>& cameras, float half_size_ratio) {
  if (cameras.empty()) throw Error("random initialisation: no cameras to place the box");
  const CameraFocus f = camera_focus(cameras);
  const float h = f.mean_distance * half_size_ratio;
  Box box;
  box.lo = f.center - glm::vec3(h);
  box.hi = f.center + glm::vec3(h);
  return box;
}

void random_points(const Box& box, size_t n, std::uint64_t seed, std::vector<glm::vec3>& points,
                   std::vector<glm::vec3>& colors) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  points.resize(n);
  colors.resize(n);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) points[i][a] = box.lo[a] + (box.hi[a] - box.lo[a]) * u(rng);
    // 3DGS draws the SH DC coefficients in [0, 1/255], so its colours start at mid grey (C0 x DC + 1/2).
    // Written out: colour_from_sh_dc(U / 255) rounds differently and would change every measured run.
    for (int c = 0; c < 3; ++c) colors[i][c] = 0.5f + kernels::kShC0 * u(rng) / 255.0f;
  }
}

}  // namespace goris
