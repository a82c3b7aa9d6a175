#pragma once
// Per-pixel maths of the screen-space glossy filter (DESIGN.md §5, paper S1.3), written once for the CPU
// driver and its CUDA twin and templated on the scalar so that the gradient tests run it in double.
//
// Level k+1 pixel (i, j) is a normal-weighted 4x4 gather of level k around its centre, which lies at level-k
// coordinate (2i + 0.5, 2j + 0.5): separable taps g = [1 3 3 1] (a [1 2 1] blur followed by a 2x2 box,
// fused so that no full-resolution blurred image is stored) times max(0, n_p . n_q)^P + eps, normalised.
// eps keeps the weight sum positive where no tap faces the same way (background pixels with zero normals
// fall back to the plain Gaussian). The normals only steer the weights and are treated as constants.
// Full-resolution pixel x samples level k at u = (x + 0.5) / 2^k - 0.5 (clamped to the level), bilinearly.
#include <cmath>

#include "core/compute/hd.h"

namespace goris::ssf {

constexpr int kMaxLevels = 8;
constexpr double kNormalWeightEps = 1e-4;

struct LevelDims {
  int h = 0, w = 0;
};

template <class T>
GORIS_HDI T tap_gauss(int s) { return (s == 0 || s == 3) ? T(1) : T(3); }

template <class T>
GORIS_HDI T pow_int(T v, int p) {
  T r = T(1);
  for (int i = 0; i < p; ++i) r *= v;
  return r;
}

// Unit length of (x, y, z), or zero when it is (almost) zero: background pixels carry no direction.
template <class T>
GORIS_HDI void unit3(T& x, T& y, T& z) {
  using std::sqrt;
  const T len = sqrt(x * x + y * y + z * z);
  const T inv = len > T(1e-12) ? T(1) / len : T(0);
  x *= inv;
  y *= inv;
  z *= inv;
}

// Unit normal of level k+1 pixel (i, j): plain [1 3 3 1]^2 average of level k's unit normals.
template <class T>
GORIS_HDI void down_normal(const T* n, LevelDims in, LevelDims out, int i, int j, T* n_out) {
  const std::size_t plane_in = std::size_t(in.h) * in.w, plane_out = std::size_t(out.h) * out.w;
  T s[3] = {T(0), T(0), T(0)};
  for (int a = 0; a < 4; ++a) {
    const int y = 2 * i - 1 + a;
    if (y < 0 || y >= in.h) continue;
    for (int b = 0; b < 4; ++b) {
      const int x = 2 * j - 1 + b;
      if (x < 0 || x >= in.w) continue;
      const T g = tap_gauss<T>(a) * tap_gauss<T>(b);
      for (int c = 0; c < 3; ++c) s[c] += g * n[c * plane_in + std::size_t(y) * in.w + x];
    }
  }
  unit3(s[0], s[1], s[2]);
  const std::size_t o = std::size_t(i) * out.w + j;
  for (int c = 0; c < 3; ++c) n_out[c * plane_out + o] = s[c];
}

// Unnormalised weight of level-k tap (y, x) for the level k+1 pixel whose unit normal is np.
template <class T>
GORIS_HDI T down_weight(const T* n, std::size_t plane_in, std::size_t q, const T* np, int a, int b, int power) {
  const T d = np[0] * n[q] + np[1] * n[plane_in + q] + np[2] * n[2 * plane_in + q];
  const T cosw = d > T(0) ? d : T(0);
  return tap_gauss<T>(a) * tap_gauss<T>(b) * (pow_int(cosw, power) + T(kNormalWeightEps));
}

// Level k+1 pixel (i, j) of all C channels from level k; writes 1 / (weight sum) for the backward pass.
template <class T>
GORIS_HDI void down_pixel(const T* x, const T* n, const T* n_next, LevelDims in, LevelDims out, int channels,
                          int power, int i, int j, T* x_out, T* inv_sum_out) {
  const std::size_t plane_in = std::size_t(in.h) * in.w, plane_out = std::size_t(out.h) * out.w;
  const std::size_t o = std::size_t(i) * out.w + j;
  const T np[3] = {n_next[o], n_next[plane_out + o], n_next[2 * plane_out + o]};
  T wsum = T(0);
  for (int a = 0; a < 4; ++a) {
    const int y = 2 * i - 1 + a;
    if (y < 0 || y >= in.h) continue;
    for (int b = 0; b < 4; ++b) {
      const int xx = 2 * j - 1 + b;
      if (xx < 0 || xx >= in.w) continue;
      wsum += down_weight(n, plane_in, std::size_t(y) * in.w + xx, np, a, b, power);
    }
  }
  const T inv = T(1) / wsum;
  inv_sum_out[o] = inv;
  for (int c = 0; c < channels; ++c) {
    const T* xc = x + c * plane_in;
    T acc = T(0);
    for (int a = 0; a < 4; ++a) {
      const int y = 2 * i - 1 + a;
      if (y < 0 || y >= in.h) continue;
      for (int b = 0; b < 4; ++b) {
        const int xx = 2 * j - 1 + b;
        if (xx < 0 || xx >= in.w) continue;
        const std::size_t q = std::size_t(y) * in.w + xx;
        acc += down_weight(n, plane_in, q, np, a, b, power) * xc[q];
      }
    }
    x_out[c * plane_out + o] = acc * inv;
  }
}

// Adjoint of down_pixel, gathered at level-k pixel (y, x): adds sum over the (at most 2x2) level k+1 pixels
// whose taps include it of weight * grad.
template <class T>
GORIS_HDI void down_adjoint_pixel(const T* n, const T* n_next, const T* inv_sum, const T* g_next, LevelDims in,
                                  LevelDims out, int channels, int power, int y, int x, T* g_x) {
  const std::size_t plane_in = std::size_t(in.h) * in.w, plane_out = std::size_t(out.h) * out.w;
  const std::size_t q = std::size_t(y) * in.w + x;
  const int i0 = (y + 1) / 2 - 1, j0 = (x + 1) / 2 - 1;  // first level k+1 row / column whose taps reach here
  for (int i = i0; i <= i0 + 1; ++i) {
    if (i < 0 || i >= out.h) continue;
    const int a = y + 1 - 2 * i;
    for (int j = j0; j <= j0 + 1; ++j) {
      if (j < 0 || j >= out.w) continue;
      const int b = x + 1 - 2 * j;
      const std::size_t o = std::size_t(i) * out.w + j;
      const T np[3] = {n_next[o], n_next[plane_out + o], n_next[2 * plane_out + o]};
      const T w = down_weight(n, plane_in, q, np, a, b, power) * inv_sum[o];
      for (int c = 0; c < channels; ++c) g_x[c * plane_in + q] += w * g_next[c * plane_out + o];
    }
  }
}

// Bilinear footprint of full-resolution coordinate `x` on a level `size` texels wide at scale 2^-k.
template <class T>
struct Tap1D {
  int i0, i1;
  T f;  // weight of i1; i0 gets 1 - f
};

template <class T>
GORIS_HDI Tap1D<T> bilinear_tap(int x, int k, int size) {
  using std::floor;
  T u = (T(x) + T(0.5)) / T(1 << k) - T(0.5);
  if (u < T(0)) u = T(0);
  if (u > T(size - 1)) u = T(size - 1);
  const int i0 = int(floor(u));
  const int i1 = i0 + 1 < size ? i0 + 1 : size - 1;
  return Tap1D<T>{i0, i1, u - T(i0)};
}

// Weight of texel `i` in a tap (both ends may be the same texel at the border).
template <class T>
GORIS_HDI T tap_weight(const Tap1D<T>& t, int i) {
  return (t.i0 == i ? T(1) - t.f : T(0)) + (t.i1 == i ? t.f : T(0));
}

// Continuous level l = R_s (L - 1) (R_s clamped to [0, 1]) as a lower level and the blend weight toward the
// next one.
template <class T>
struct LevelBlend {
  int k0;
  T t;
};

template <class T>
GORIS_HDI LevelBlend<T> level_blend(T rs, int levels) {
  using std::floor;
  T r = rs < T(0) ? T(0) : (rs > T(1) ? T(1) : rs);
  const T l = r * T(levels - 1);
  int k0 = int(floor(l));
  if (k0 > levels - 2) k0 = levels - 2;
  return LevelBlend<T>{k0, l - T(k0)};
}

// Level k of channel c sampled at full-resolution pixel (y, x). Level 0 is read directly, so R_s = 0 gives
// the input exactly.
template <class T>
GORIS_HDI T sample_level(const T* level, LevelDims d, int c, int k, int y, int x) {
  const std::size_t plane = std::size_t(d.h) * d.w;
  const T* p = level + c * plane;
  if (k == 0) return p[std::size_t(y) * d.w + x];
  const Tap1D<T> ty = bilinear_tap<T>(y, k, d.h), tx = bilinear_tap<T>(x, k, d.w);
  const T r0 = (T(1) - tx.f) * p[std::size_t(ty.i0) * d.w + tx.i0] + tx.f * p[std::size_t(ty.i0) * d.w + tx.i1];
  const T r1 = (T(1) - tx.f) * p[std::size_t(ty.i1) * d.w + tx.i0] + tx.f * p[std::size_t(ty.i1) * d.w + tx.i1];
  return (T(1) - ty.f) * r0 + ty.f * r1;
}

// Pointers to every level of one pyramid, passed by value into kernels.
template <class T>
struct LevelSet {
  const T* p[kMaxLevels];
  LevelDims d[kMaxLevels];
  int levels;
};

// out(c, y, x) for every channel of full-resolution pixel (y, x).
template <class T>
GORIS_HDI void sample_pixel(const LevelSet<T>& L, const T* rs, int channels, int y, int x, T* out) {
  const int H = L.d[0].h, W = L.d[0].w;
  const std::size_t plane = std::size_t(H) * W, o = std::size_t(y) * W + x;
  const LevelBlend<T> lb = level_blend(rs[o], L.levels);
  for (int c = 0; c < channels; ++c) {
    const T a = sample_level(L.p[lb.k0], L.d[lb.k0], c, lb.k0, y, x);
    const T b = sample_level(L.p[lb.k0 + 1], L.d[lb.k0 + 1], c, lb.k0 + 1, y, x);
    out[c * plane + o] = (T(1) - lb.t) * a + lb.t * b;
  }
}

// dL/dR_s at full-resolution pixel (y, x): sum_c g_c (S_{k0+1} - S_{k0}) (L - 1), zero where R_s was clamped.
template <class T>
GORIS_HDI T sample_grad_rs(const LevelSet<T>& L, const T* rs, const T* g_out, int channels, int y, int x) {
  const int H = L.d[0].h, W = L.d[0].w;
  const std::size_t plane = std::size_t(H) * W, o = std::size_t(y) * W + x;
  if (rs[o] < T(0) || rs[o] > T(1)) return T(0);
  const LevelBlend<T> lb = level_blend(rs[o], L.levels);
  T acc = T(0);
  for (int c = 0; c < channels; ++c) {
    const T a = sample_level(L.p[lb.k0], L.d[lb.k0], c, lb.k0, y, x);
    const T b = sample_level(L.p[lb.k0 + 1], L.d[lb.k0 + 1], c, lb.k0 + 1, y, x);
    acc += g_out[c * plane + o] * (b - a);
  }
  return acc * T(L.levels - 1);
}

// Adjoint of the sampling for texel (i, j) of level k >= 1: gathers every full-resolution pixel whose
// bilinear footprint on level k includes the texel, times that pixel's weight for level k. Writes (not adds).
template <class T>
GORIS_HDI void sample_adjoint_texel(const T* rs, const T* g_out, int H, int W, int levels, int k, LevelDims d,
                                    int channels, int i, int j, T* g_level) {
  using std::ceil;
  using std::floor;
  const T s = T(1 << k);
  const int y_lo = int(floor((T(i) - T(0.5)) * s - T(0.5))), y_hi = int(ceil((T(i) + T(1.5)) * s - T(0.5)));
  const int x_lo = int(floor((T(j) - T(0.5)) * s - T(0.5))), x_hi = int(ceil((T(j) + T(1.5)) * s - T(0.5)));
  const std::size_t plane = std::size_t(H) * W, lplane = std::size_t(d.h) * d.w;
  for (int c = 0; c < channels; ++c) g_level[c * lplane + std::size_t(i) * d.w + j] = T(0);
  for (int y = y_lo > 0 ? y_lo : 0; y <= (y_hi < H - 1 ? y_hi : H - 1); ++y) {
    const T wy = tap_weight(bilinear_tap<T>(y, k, d.h), i);
    if (wy == T(0)) continue;
    for (int x = x_lo > 0 ? x_lo : 0; x <= (x_hi < W - 1 ? x_hi : W - 1); ++x) {
      const std::size_t o = std::size_t(y) * W + x;
      const LevelBlend<T> lb = level_blend(rs[o], levels);
      const T lw = lb.k0 == k ? T(1) - lb.t : (lb.k0 + 1 == k ? lb.t : T(0));
      if (lw == T(0)) continue;
      const T w = wy * lw * tap_weight(bilinear_tap<T>(x, k, d.w), j);
      for (int c = 0; c < channels; ++c) g_level[c * lplane + std::size_t(i) * d.w + j] += w * g_out[c * plane + o];
    }
  }
}

// Level-0 part of the sampling adjoint at full-resolution pixel (y, x) for every channel (writes).
template <class T>
GORIS_HDI void sample_adjoint_level0(const T* rs, const T* g_out, int H, int W, int levels, int channels, int y,
                                     int x, T* g_level0) {
  const std::size_t plane = std::size_t(H) * W, o = std::size_t(y) * W + x;
  const LevelBlend<T> lb = level_blend(rs[o], levels);
  const T lw = lb.k0 == 0 ? T(1) - lb.t : T(0);
  for (int c = 0; c < channels; ++c) g_level0[c * plane + o] = lw * g_out[c * plane + o];
}

}  // namespace goris::ssf
