#include "train/losses/intrinsic_losses.h"

#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace goris {

namespace {

template <class T>
T sign(T v) {
  return v > T(0) ? T(1) : (v < T(0) ? T(-1) : T(0));
}

// Per-pixel normalisation of a [3][H][W] vector image and its adjoint.
template <class T>
struct Normalized {
  std::vector<T> u;     // [3][H][W] unit vectors (0 where degenerate)
  std::vector<T> inv;   // [H][W] 1 / |x| (0 where degenerate)
  Normalized(const T* x, std::size_t hw) : u(3 * hw, T(0)), inv(hw, T(0)) {
    for (std::size_t p = 0; p < hw; ++p) {
      const T a = x[p], b = x[hw + p], c = x[2 * hw + p];
      const T len = std::sqrt(a * a + b * b + c * c);
      if (!(len > T(1e-8))) continue;
      inv[p] = T(1) / len;
      u[p] = a / len;
      u[hw + p] = b / len;
      u[2 * hw + p] = c / len;
    }
  }
  // grad_x += (I - u u^T) / |x| * g for the pixel's 3-vector g (strided by hw).
  void backward(const T* g, std::size_t hw, T* grad_x) const {
    for (std::size_t p = 0; p < hw; ++p) {
      if (inv[p] == T(0)) continue;
      const T d = u[p] * g[p] + u[hw + p] * g[hw + p] + u[2 * hw + p] * g[2 * hw + p];
      for (int c = 0; c < 3; ++c) grad_x[c * hw + p] += (g[c * hw + p] - u[c * hw + p] * d) * inv[p];
    }
  }
};

}  // namespace

template <class T>
T normal_prior_loss(const T* normal, const T* prior, const T* mask, int width, int height, T* grad_normal, T weight) {
  const std::size_t hw = std::size_t(width) * std::size_t(height);
  if (hw == 0) return T(0);
  const Normalized<T> n(normal, hw);
  const T norm = T(1) / T(hw);
  T loss = T(0);
  std::vector<T> g(grad_normal ? 3 * hw : 0, T(0));
  for (std::size_t p = 0; p < hw; ++p) {
    if (mask[p] == T(0) || n.inv[p] == T(0)) continue;
    for (int c = 0; c < 3; ++c) {
      const T d = n.u[c * hw + p] - prior[c * hw + p];
      loss += mask[p] * std::abs(d);
      if (grad_normal) g[c * hw + p] = weight * norm * mask[p] * sign(d);
    }
  }
  if (grad_normal) n.backward(g.data(), hw, grad_normal);
  return loss * norm;
}

template <class T>
T edge_aware_smoothness(const T* x, int channels, const T* image, const T* mask, int width, int height, T* grad_x,
                        T weight, bool normalize_x) {
  const std::size_t hw = std::size_t(width) * std::size_t(height);
  if (hw == 0) return T(0);
  std::optional<Normalized<T>> n;
  if (normalize_x) n.emplace(x, hw);
  const T* xs = normalize_x ? n->u.data() : x;
  std::vector<T> g;
  T* gx = grad_x;
  if (grad_x && normalize_x) {
    g.assign(std::size_t(channels) * hw, T(0));
    gx = g.data();
  }
  const T norm = T(1) / T(hw);
  T loss = T(0);
  auto term = [&](std::size_t p, std::size_t q) {
    if (mask[p] == T(0)) return;
    if (normalize_x && (n->inv[p] == T(0) || n->inv[q] == T(0))) return;
    T edge = T(0);
    for (int c = 0; c < 3; ++c) edge += std::abs(image[c * hw + q] - image[c * hw + p]);
    const T wgt = mask[p] * std::exp(-edge / T(3));
    for (int c = 0; c < channels; ++c) {
      const T d = xs[c * hw + q] - xs[c * hw + p];
      loss += wgt * std::abs(d);
      if (gx) {
        const T s = weight * norm * wgt * sign(d);
        gx[c * hw + q] += s;
        gx[c * hw + p] -= s;
      }
    }
  };
  for (int y = 0; y < height; ++y)
    for (int xx = 0; xx < width; ++xx) {
      const std::size_t p = std::size_t(y) * width + xx;
      if (xx + 1 < width) term(p, p + 1);
      if (y + 1 < height) term(p, p + std::size_t(width));
    }
  if (grad_x && normalize_x) n->backward(gx, hw, grad_x);
  return loss * norm;
}

template <class T>
T region_loss(const T* region, const T* glossy_mask, int width, int height, T* grad_region, T weight) {
  const std::size_t hw = std::size_t(width) * std::size_t(height);
  if (hw == 0) return T(0);
  const T norm = T(1) / T(hw);
  T loss = T(0);
  for (std::size_t p = 0; p < hw; ++p) {
    loss += glossy_mask[p] * region[p];
    if (grad_region) grad_region[p] += weight * norm * glossy_mask[p];
  }
  return loss * norm;
}

template <class T>
T label_bce_loss(const T* label, const T* object_mask, int width, int height, T* grad_label, T weight, T eps) {
  const std::size_t hw = std::size_t(width) * std::size_t(height);
  if (hw == 0) return T(0);
  const T norm = T(1) / T(hw);
  T loss = T(0);
  for (std::size_t p = 0; p < hw; ++p) {
    const T y = object_mask[p];
    const bool inside = label[p] > eps && label[p] < T(1) - eps;
    const T l = inside ? label[p] : (label[p] <= eps ? eps : T(1) - eps);
    loss -= y * std::log(l) + (T(1) - y) * std::log(T(1) - l);
    if (grad_label && inside) grad_label[p] += weight * norm * (-y / l + (T(1) - y) / (T(1) - l));
  }
  return loss * norm;
}

#define GORIS_INTRINSIC_LOSSES(T)                                                                              \
  template T normal_prior_loss<T>(const T*, const T*, const T*, int, int, T*, T);                            \
  template T edge_aware_smoothness<T>(const T*, int, const T*, const T*, int, int, T*, T, bool);             \
  template T region_loss<T>(const T*, const T*, int, int, T*, T);                                            \
  template T label_bce_loss<T>(const T*, const T*, int, int, T*, T, T);
GORIS_INTRINSIC_LOSSES(float)
GORIS_INTRINSIC_LOSSES(double)
#undef GORIS_INTRINSIC_LOSSES

}  // namespace goris
