// Per-attribute differences between two models (core/io/splat_compare.h).
#include "core/io/splat_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include "core/util/error.h"

namespace goris {

std::vector<uint32_t> match_by_position(const GaussianPly& ref, const GaussianPly& got) {
  if (ref.count != got.count)
    throw Error("compare", std::to_string(got.count) + " Gaussians against " + std::to_string(ref.count));
  // Reference points sorted by x; each query scans outwards from its x until |dx| exceeds the best distance.
  std::vector<uint32_t> by_x(ref.count);
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::sort(by_x.begin(), by_x.end(), [&](uint32_t a, uint32_t b) { return ref.positions[a * 3] < ref.positions[b * 3]; });
  std::vector<float> xs(ref.count);
  for (size_t k = 0; k < ref.count; ++k) xs[k] = ref.positions[by_x[k] * 3];
  std::vector<uint32_t> order(got.count);
  for (size_t i = 0; i < got.count; ++i) {
    const float* p = &got.positions[i * 3];
    const size_t start = size_t(std::lower_bound(xs.begin(), xs.end(), p[0]) - xs.begin());
    double best = INFINITY;
    uint32_t best_k = 0;
    auto visit = [&](size_t k) {
      const float* q = &ref.positions[by_x[k] * 3];
      const double d = double(p[0] - q[0]) * (p[0] - q[0]) + double(p[1] - q[1]) * (p[1] - q[1]) +
                       double(p[2] - q[2]) * (p[2] - q[2]);
      if (d < best) best = d, best_k = by_x[k];
    };
    for (size_t k = start; k < xs.size() && double(xs[k] - p[0]) * (xs[k] - p[0]) <= best; ++k) visit(k);
    for (size_t k = start; k-- > 0 && double(p[0] - xs[k]) * (p[0] - xs[k]) <= best;) visit(k);
    order[i] = best_k;
  }
  return order;
}

ModelDiff compare_models(const GaussianPly& ref, const GaussianPly& got, const std::vector<uint32_t>& order) {
  if (ref.count != got.count)
    throw Error("compare", std::to_string(got.count) + " Gaussians against " + std::to_string(ref.count));
  if (!order.empty() && order.size() != got.count) throw Error("compare", "the order does not match the count");
  ModelDiff d;
  d.count = got.count;
  const size_t rr = GaussianPly::rest_per_gaussian(ref.sh_degree) / 3, gr = GaussianPly::rest_per_gaussian(got.sh_degree) / 3;
  const size_t common = std::min(rr, gr);
  auto add = [](AttributeError& e, double v, size_t i) {
    if (v > e.max) e.max = v, e.worst = i;
    e.mean += v;
  };
  // The rotation matrix of a quaternion w x y z (normalised here).
  auto matrix = [](const float* q, double m[3][3]) {
    double n = 0;
    for (int k = 0; k < 4; ++k) n += double(q[k]) * q[k];
    n = n > 0 ? std::sqrt(n) : 1;
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    std::memcpy(m, r, sizeof r);
  };
  for (size_t i = 0; i < got.count; ++i) {
    const size_t j = order.empty() ? i : order[i];
    double dp = 0, ds = 0, dc = 0, dr = 0;
    for (int a = 0; a < 3; ++a) {
      const double e = double(got.positions[i * 3 + a]) - ref.positions[j * 3 + a];
      dp += e * e;
      ds = std::max(ds, std::abs(double(got.scales[i * 3 + a]) - ref.scales[j * 3 + a]));
      dc = std::max(dc, std::abs(double(got.f_dc[i * 3 + a]) - ref.f_dc[j * 3 + a]));
    }
    // Each principal axis (a column of the rotation) against its counterpart, up to sign: q and -q, and
    // half-turns about an axis (which leave the ellipsoid as it is) are the same Gaussian.
    double ma[3][3], mb[3][3], angle = 0;
    matrix(&got.rotations[i * 4], ma);
    matrix(&ref.rotations[j * 4], mb);
    for (int axis = 0; axis < 3; ++axis) {
      const double dot = ma[0][axis] * mb[0][axis] + ma[1][axis] * mb[1][axis] + ma[2][axis] * mb[2][axis];
      angle = std::max(angle, std::acos(std::min(1.0, std::abs(dot))) * 180.0 / M_PI);
    }
    for (int c = 0; c < 3; ++c)
      for (size_t k = 0; k < common; ++k)
        dr = std::max(dr, std::abs(double(got.f_rest[i * gr * 3 + c * gr + k]) - ref.f_rest[j * rr * 3 + c * rr + k]));
    const double oa = 1.0 / (1.0 + std::exp(-double(got.opacity[i]))), ob = 1.0 / (1.0 + std::exp(-double(ref.opacity[j])));
    add(d.position, std::sqrt(dp), i);
    add(d.scale, ds, i);
    add(d.rotation, angle, i);
    add(d.opacity, std::abs(oa - ob), i);
    add(d.f_dc, dc, i);
    add(d.f_rest, dr, i);
  }
  if (got.count)
    for (AttributeError* e : {&d.position, &d.scale, &d.rotation, &d.opacity, &d.f_dc, &d.f_rest}) e->mean /= double(got.count);
  return d;
}

std::string ModelDiff::table() const {
  std::string s;
  auto line = [&](const char* name, const AttributeError& e, const char* unit) {
    char b[160];
    std::snprintf(b, sizeof b, "  %-9s max %-11.4g mean %-11.4g (%s; worst: Gaussian %zu)\n", name, e.max, e.mean, unit, e.worst);
    s += b;
  };
  line("position", position, "distance");
  line("scale", scale, "log scale");
  line("rotation", rotation, "degrees");
  line("opacity", opacity, "after sigmoid");
  line("f_dc", f_dc, "SH DC");
  line("f_rest", f_rest, "SH rest");
  return s;
}

}  // namespace goris
