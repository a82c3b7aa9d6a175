#include "train/losses/depth_normal_loss.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace goris {

namespace {

template <class T>
struct V3 {
  T x = 0, y = 0, z = 0;
};
template <class T>
V3<T> operator+(V3<T> a, V3<T> b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T>
V3<T> operator-(V3<T> a, V3<T> b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
V3<T> operator*(T s, V3<T> a) { return {s * a.x, s * a.y, s * a.z}; }
template <class T>
T dot(V3<T> a, V3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T>
V3<T> cross(V3<T> a, V3<T> b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// Shared geometry of one image: back-projection and the un-normalised depth normal of a pixel.
template <class T>
struct DepthGeometry {
  const T* depth;
  int w, h;
  T fx, fy, cx, cy;
  V3<T> ray(int x, int y) const { return {(T(x) + T(0.5) - cx) / fx, (T(y) + T(0.5) - cy) / fy, T(1)}; }
  V3<T> point(int x, int y) const { return depth[size_t(y) * w + x] * ray(x, y); }
  bool interior(int x, int y) const { return x >= 1 && y >= 1 && x + 1 < w && y + 1 < h; }
  void differences(int x, int y, V3<T>& dx, V3<T>& dy) const {
    dx = point(x + 1, y) - point(x - 1, y);
    dy = point(x, y + 1) - point(x, y - 1);
  }
};

}  // namespace

template <class T>
T depth_normal_loss(const T* depth, const T* normal, const T* pixel_weight, int width, int height, T fx, T fy, T cx,
                    T cy, T* grad_depth, T* grad_normal, T weight) {
  if (width < 3 || height < 3) return T(0);
  const size_t hw = size_t(width) * size_t(height);
  const DepthGeometry<T> geo{depth, width, height, fx, fy, cx, cy};
  const double interior_count = double(width - 2) * double(height - 2);
  const bool want_grad = grad_depth || grad_normal;
  const T gscale = weight / T(interior_count);
  // Per-pixel gradients on the differences dx, dy, gathered onto the depth in a second pass (no races).
  std::vector<V3<T>> g_dx(want_grad ? hw : 0), g_dy(want_grad ? hw : 0);

  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<int>(1, height - 1), 0.0,
      [&](const tbb::blocked_range<int>& rows, double acc) {
        for (int y = rows.begin(); y != rows.end(); ++y)
          for (int x = 1; x + 1 < width; ++x) {
            const size_t p = size_t(y) * width + x;
            const T wp = pixel_weight ? pixel_weight[p] : T(1);
            if (wp == T(0)) continue;
            V3<T> dx, dy;
            geo.differences(x, y, dx, dy);
            const V3<T> c = cross(dy, dx);
            const V3<T> nr{normal[p], normal[hw + p], normal[2 * hw + p]};
            const T lc = std::sqrt(dot(c, c)), ln = std::sqrt(dot(nr, nr));
            if (!(lc > T(0)) || !(ln > T(0))) continue;
            const V3<T> nd = (T(1) / lc) * c, n = (T(1) / ln) * nr;
            const T cosv = dot(n, nd);
            acc += double(wp * (T(1) - cosv));
            if (!want_grad) continue;
            const T g = -gscale * wp;  // d(loss)/d(cos)
            // d cos / d nr = (nd - n cos) / |nr|, d cos / d c = (n - nd cos) / |c|.
            if (grad_normal) {
              const V3<T> gn = (g / ln) * (nd - cosv * n);
              grad_normal[p] += gn.x;
              grad_normal[hw + p] += gn.y;
              grad_normal[2 * hw + p] += gn.z;
            }
            const V3<T> gc = (g / lc) * (n - cosv * nd);
            // c = dy x dx: dL/ddy = dx x gc, dL/ddx = gc x dy.
            g_dy[p] = cross(dx, gc);
            g_dx[p] = cross(gc, dy);
          }
        return acc;
      },
      [](double a, double b) { return a + b; });

  if (grad_depth) {
    tbb::parallel_for(0, height, [&](int y) {
      for (int x = 0; x < width; ++x) {
        // P(x, y) enters dx of (x-1, y) with +, of (x+1, y) with -, dy of (x, y-1) with +, of (x, y+1) with -.
        V3<T> gp;
        if (geo.interior(x - 1, y)) gp = gp + g_dx[size_t(y) * width + x - 1];
        if (geo.interior(x + 1, y)) gp = gp - g_dx[size_t(y) * width + x + 1];
        if (geo.interior(x, y - 1)) gp = gp + g_dy[size_t(y - 1) * width + x];
        if (geo.interior(x, y + 1)) gp = gp - g_dy[size_t(y + 1) * width + x];
        grad_depth[size_t(y) * width + x] += dot(gp, geo.ray(x, y));
      }
    });
  }
  return T(sum / interior_count);
}

template <class T>
T rendered_depth_normal_loss(const T* depth_weighted, const T* alpha, const T* median_depth, const T* normal,
                             int width, int height, T fx, T fy, T cx, T cy, T median_ratio, T* grad_depth,
                             T* grad_alpha, T* grad_median, T* grad_normal, T weight, T min_alpha) {
  const size_t hw = size_t(width) * size_t(height);
  std::vector<T> expected(hw), g_expected(hw, T(0));
  for (size_t p = 0; p < hw; ++p) expected[p] = depth_weighted[p] / std::max(alpha[p], min_alpha);
  const bool want = grad_depth || grad_alpha;
  const T l_exp = depth_normal_loss<T>(expected.data(), normal, alpha, width, height, fx, fy, cx, cy,
                                       want ? g_expected.data() : nullptr, grad_normal, weight * (T(1) - median_ratio));
  const T l_med = depth_normal_loss<T>(median_depth, normal, alpha, width, height, fx, fy, cx, cy, grad_median,
                                       grad_normal, weight * median_ratio);
  if (want)
    for (size_t p = 0; p < hw; ++p) {
      const T a = alpha[p];
      if (a <= min_alpha) {  // the clamp: the division no longer depends on alpha
        if (grad_depth) grad_depth[p] += g_expected[p] / min_alpha;
      } else {
        if (grad_depth) grad_depth[p] += g_expected[p] / a;
        if (grad_alpha) grad_alpha[p] -= g_expected[p] * depth_weighted[p] / (a * a);
      }
    }
  return (T(1) - median_ratio) * l_exp + median_ratio * l_med;
}

template <class T>
void normal_from_depth(const T* depth, int width, int height, T fx, T fy, T cx, T cy, T* out) {
  const size_t hw = size_t(width) * size_t(height);
  const DepthGeometry<T> geo{depth, width, height, fx, fy, cx, cy};
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * width + x;
      V3<T> n;
      if (geo.interior(x, y)) {
        V3<T> dx, dy;
        geo.differences(x, y, dx, dy);
        const V3<T> c = cross(dy, dx);
        const T l = std::sqrt(dot(c, c));
        if (l > T(0)) n = (T(1) / l) * c;
      }
      out[p] = n.x;
      out[hw + p] = n.y;
      out[2 * hw + p] = n.z;
    }
  });
}

#define GORIS_INSTANTIATE(T)                                                                              \
  template T depth_normal_loss<T>(const T*, const T*, const T*, int, int, T, T, T, T, T*, T*, T);          \
  template void normal_from_depth<T>(const T*, int, int, T, T, T, T, T*);                                  \
  template T rendered_depth_normal_loss<T>(const T*, const T*, const T*, const T*, int, int, T, T, T, T, T, T*, T*, \
                                           T*, T*, T, T);
GORIS_INSTANTIATE(float)
GORIS_INSTANTIATE(double)
#undef GORIS_INSTANTIATE

}  // namespace goris
