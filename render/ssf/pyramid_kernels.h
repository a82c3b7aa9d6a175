#pragma once
// Per-pixel maths of the screen-space glossy filter (docs/design/maths.md, Screen-space glossy filter; paper
// S1.3), written once for the CPU driver and its CUDA twin and templated on the scalar so that the gradient
// tests run it in double.
//
// Level k+1 pixel (i, j) is a normal-weighted 4x4 gather of level k around its centre, which lies at level-k
// coordinate (2i + 0.5, 2j + 0.5): separable taps g = [1 3 3 1] (a [1 2 1] blur followed by a 2x2 box,
// fused so that no full-resolution blurred image is stored) times max(0, n_p . n_q)^P + eps, normalised.
// eps keeps the weight sum positive where no tap faces the same way (background pixels with zero normals
// fall back to the plain Gaussian). The normals only steer the weights and are treated as constants.
// Full-resolution pixel x samples level k at u = (x + 0.5) / 2^k - 0.5 (clamped to the level), bilinearly.
//
// Weighted pyramid (normalised convolution): an optional mass m >= 0 per level-0 pixel says how much its
// value counts (coarse tracing: 0 where no ray was traced, 1 elsewhere). Every blur then weighs tap q by
// w_q m_q and divides by the sum of those weights, each coarser texel carries the mass
// sum(w_q m_q) / sum(w_q) (the share of its footprint that had data), and the bilinear lookups weigh their
// four texels by mass too (normalised), so untraced pixels never enter a value. Texels without any mass are 0 (and pass
// no gradient). The masses are constants: forward and backward stay exact for a given mass image. A null
// mass pointer is the unweighted pyramid (every m = 1), computed exactly as without masses.
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

// Mass of texel q; a null plane is the unweighted pyramid.
template <class T>
GORIS_HDI T mass_at(const T* m, std::size_t q) { return m ? m[q] : T(1); }

// Unnormalised weight of level-k tap (y, x) for the level k+1 pixel whose unit normal is np.
template <class T>
GORIS_HDI T down_weight(const T* n, std::size_t plane_in, std::size_t q, const T* np, int a, int b, int power) {
  const T d = np[0] * n[q] + np[1] * n[plane_in + q] + np[2] * n[2 * plane_in + q];
  const T cosw = d > T(0) ? d : T(0);
  return tap_gauss<T>(a) * tap_gauss<T>(b) * (pow_int(cosw, power) + T(kNormalWeightEps));
}

// Level k+1 pixel (i, j) of all C channels from level k (masses m, null = unweighted); writes 1 / (weight
// sum) for the backward pass (0 where no tap has mass) and, when weighted, the texel's mass into m_out.
template <class T>
GORIS_HDI void down_pixel(const T* x, const T* m, const T* n, const T* n_next, LevelDims in, LevelDims out,
                          int channels, int power, int i, int j, T* x_out, T* inv_sum_out, T* m_out) {
  const std::size_t plane_in = std::size_t(in.h) * in.w, plane_out = std::size_t(out.h) * out.w;
  const std::size_t o = std::size_t(i) * out.w + j;
  const T np[3] = {n_next[o], n_next[plane_out + o], n_next[2 * plane_out + o]};
  T wsum = T(0), wall = T(0);
  for (int a = 0; a < 4; ++a) {
    const int y = 2 * i - 1 + a;
    if (y < 0 || y >= in.h) continue;
    for (int b = 0; b < 4; ++b) {
      const int xx = 2 * j - 1 + b;
      if (xx < 0 || xx >= in.w) continue;
      const std::size_t q = std::size_t(y) * in.w + xx;
      const T w = down_weight(n, plane_in, q, np, a, b, power);
      wall += w;
      wsum += m ? w * m[q] : w;
    }
  }
  const T inv = wsum > T(0) ? T(1) / wsum : T(0);
  inv_sum_out[o] = inv;
  if (m_out) m_out[o] = wsum / wall;
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
        const T w = down_weight(n, plane_in, q, np, a, b, power);
        acc += (m ? w * m[q] : w) * xc[q];
      }
    }
    x_out[c * plane_out + o] = acc * inv;
  }
}

// Adjoint of down_pixel, gathered at level-k pixel (y, x): adds sum over the (at most 2x2) level k+1 pixels
// whose taps include it of weight * grad.
template <class T>
GORIS_HDI void down_adjoint_pixel(const T* m, const T* n, const T* n_next, const T* inv_sum, const T* g_next,
                                  LevelDims in, LevelDims out, int channels, int power, int y, int x, T* g_x) {
  const std::size_t plane_in = std::size_t(in.h) * in.w, plane_out = std::size_t(out.h) * out.w;
  const std::size_t q = std::size_t(y) * in.w + x;
  const T mq = mass_at(m, q);
  if (mq == T(0)) return;  // an untraced pixel enters no texel
  const int i0 = (y + 1) / 2 - 1, j0 = (x + 1) / 2 - 1;  // first level k+1 row / column whose taps reach here
  for (int i = i0; i <= i0 + 1; ++i) {
    if (i < 0 || i >= out.h) continue;
    const int a = y + 1 - 2 * i;
    for (int j = j0; j <= j0 + 1; ++j) {
      if (j < 0 || j >= out.w) continue;
      const int b = x + 1 - 2 * j;
      const std::size_t o = std::size_t(i) * out.w + j;
      const T np[3] = {n_next[o], n_next[plane_out + o], n_next[2 * plane_out + o]};
      const T w = down_weight(n, plane_in, q, np, a, b, power) * mq * inv_sum[o];
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

// 1 / (sum of the bilinear weights times the texel masses) of full-resolution pixel (y, x) on level k >= 1:
// the normalisation of a weighted lookup (0 where none of the four texels has mass). Computed once per pixel
// and level in the forward pass (sample_norm) and kept for the backward pass.
template <class T>
GORIS_HDI T footprint_inv_mass(const T* m, LevelDims d, int k, int y, int x) {
  const Tap1D<T> ty = bilinear_tap<T>(y, k, d.h), tx = bilinear_tap<T>(x, k, d.w);
  const T r0 = (T(1) - tx.f) * m[std::size_t(ty.i0) * d.w + tx.i0] + tx.f * m[std::size_t(ty.i0) * d.w + tx.i1];
  const T r1 = (T(1) - tx.f) * m[std::size_t(ty.i1) * d.w + tx.i0] + tx.f * m[std::size_t(ty.i1) * d.w + tx.i1];
  const T sum = (T(1) - ty.f) * r0 + ty.f * r1;
  return sum > T(0) ? T(1) / sum : T(0);
}

// Level k of channel c sampled at full-resolution pixel (y, x). Unweighted (m null): bilinear. Weighted:
// each texel's weight times its mass, times norm = footprint_inv_mass(...) of this pixel and level. Level 0
// is read directly, so R_s = 0 gives the input exactly (0 at a pixel without mass).
template <class T>
GORIS_HDI T sample_level(const T* level, const T* m, T norm, LevelDims d, int c, int k, int y, int x) {
  const std::size_t plane = std::size_t(d.h) * d.w;
  const T* p = level + c * plane;
  if (k == 0) {
    const std::size_t o = std::size_t(y) * d.w + x;
    return m && !(m[o] > T(0)) ? T(0) : p[o];
  }
  const Tap1D<T> ty = bilinear_tap<T>(y, k, d.h), tx = bilinear_tap<T>(x, k, d.w);
  const std::size_t q00 = std::size_t(ty.i0) * d.w + tx.i0, q01 = std::size_t(ty.i0) * d.w + tx.i1;
  const std::size_t q10 = std::size_t(ty.i1) * d.w + tx.i0, q11 = std::size_t(ty.i1) * d.w + tx.i1;
  if (!m) {
    const T r0 = (T(1) - tx.f) * p[q00] + tx.f * p[q01];
    const T r1 = (T(1) - tx.f) * p[q10] + tx.f * p[q11];
    return (T(1) - ty.f) * r0 + ty.f * r1;
  }
  const T r0 = (T(1) - tx.f) * m[q00] * p[q00] + tx.f * m[q01] * p[q01];
  const T r1 = (T(1) - tx.f) * m[q10] * p[q10] + tx.f * m[q11] * p[q11];
  return ((T(1) - ty.f) * r0 + ty.f * r1) * norm;
}

// Pointers to every level of one pyramid, passed by value into kernels; for a weighted pyramid also the
// masses of every level and, for k >= 1, the full-resolution lookup normalisations (all null when unweighted).
template <class T>
struct LevelSet {
  const T* p[kMaxLevels];
  const T* m[kMaxLevels];
  const T* norm[kMaxLevels];
  LevelDims d[kMaxLevels];
  int levels;
  GORIS_HD T norm_at(int k, std::size_t o) const { return norm[k] ? norm[k][o] : T(1); }
};

// out(c, y, x) for every channel of full-resolution pixel (y, x).
template <class T>
GORIS_HDI void sample_pixel(const LevelSet<T>& L, const T* rs, int channels, int y, int x, T* out) {
  const int H = L.d[0].h, W = L.d[0].w;
  const std::size_t plane = std::size_t(H) * W, o = std::size_t(y) * W + x;
  const LevelBlend<T> lb = level_blend(rs[o], L.levels);
  const int k0 = lb.k0, k1 = lb.k0 + 1;
  const T n0 = L.norm_at(k0, o), n1 = L.norm_at(k1, o);
  for (int c = 0; c < channels; ++c) {
    const T a = sample_level(L.p[k0], L.m[k0], n0, L.d[k0], c, k0, y, x);
    const T b = sample_level(L.p[k1], L.m[k1], n1, L.d[k1], c, k1, y, x);
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
  const int k0 = lb.k0, k1 = lb.k0 + 1;
  const T n0 = L.norm_at(k0, o), n1 = L.norm_at(k1, o);
  T acc = T(0);
  for (int c = 0; c < channels; ++c) {
    const T a = sample_level(L.p[k0], L.m[k0], n0, L.d[k0], c, k0, y, x);
    const T b = sample_level(L.p[k1], L.m[k1], n1, L.d[k1], c, k1, y, x);
    acc += g_out[c * plane + o] * (b - a);
  }
  return acc * T(L.levels - 1);
}

// Adjoint of the sampling for texel (i, j) of level k >= 1 (weighted: its mass m_t and the pixels'
// normalisations norm, full resolution; both null when unweighted): gathers every full-resolution pixel
// whose bilinear footprint on level k includes the texel, times that pixel's weight for it. Writes (not adds).
template <class T>
GORIS_HDI void sample_adjoint_texel(const T* rs, const T* g_out, int H, int W, int levels, int k, LevelDims d,
                                    const T* m, const T* norm, int channels, int i, int j, T* g_level) {
  using std::ceil;
  using std::floor;
  const T s = T(1 << k);
  const int y_lo = int(floor((T(i) - T(0.5)) * s - T(0.5))), y_hi = int(ceil((T(i) + T(1.5)) * s - T(0.5)));
  const int x_lo = int(floor((T(j) - T(0.5)) * s - T(0.5))), x_hi = int(ceil((T(j) + T(1.5)) * s - T(0.5)));
  const std::size_t plane = std::size_t(H) * W, lplane = std::size_t(d.h) * d.w, t = std::size_t(i) * d.w + j;
  for (int c = 0; c < channels; ++c) g_level[c * lplane + t] = T(0);
  const T mt = m ? m[t] : T(1);
  if (!(mt > T(0))) return;
  for (int y = y_lo > 0 ? y_lo : 0; y <= (y_hi < H - 1 ? y_hi : H - 1); ++y) {
    const T wy = tap_weight(bilinear_tap<T>(y, k, d.h), i);
    if (wy == T(0)) continue;
    for (int x = x_lo > 0 ? x_lo : 0; x <= (x_hi < W - 1 ? x_hi : W - 1); ++x) {
      const std::size_t o = std::size_t(y) * W + x;
      const LevelBlend<T> lb = level_blend(rs[o], levels);
      const T lw = lb.k0 == k ? T(1) - lb.t : (lb.k0 + 1 == k ? lb.t : T(0));
      if (lw == T(0)) continue;
      T w = wy * lw * tap_weight(bilinear_tap<T>(x, k, d.w), j);
      if (m) w *= mt * norm[o];
      for (int c = 0; c < channels; ++c) g_level[c * lplane + t] += w * g_out[c * plane + o];
    }
  }
}

// Level-0 part of the sampling adjoint at full-resolution pixel (y, x) for every channel (writes); m: level
// 0's masses or null.
template <class T>
GORIS_HDI void sample_adjoint_level0(const T* rs, const T* g_out, const T* m, int H, int W, int levels, int channels,
                                     int y, int x, T* g_level0) {
  const std::size_t plane = std::size_t(H) * W, o = std::size_t(y) * W + x;
  const LevelBlend<T> lb = level_blend(rs[o], levels);
  const T lw = lb.k0 == 0 && !(m && !(m[o] > T(0))) ? T(1) - lb.t : T(0);
  for (int c = 0; c < channels; ++c) g_level0[c * plane + o] = lw * g_out[c * plane + o];
}

}  // namespace goris::ssf
