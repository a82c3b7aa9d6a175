#pragma once
// Per-lookup maths of the prefiltered environment cube map, shared by the CPU and CUDA drivers and
// templated on the scalar type (double in the gradient tests).
//
// Layout of a mip chain: levels k = 0..L-1 stored one after the other, level k is [6][r_k][r_k][3] with
// r_k = R >> k (R a power of two), texel (face, y, x, channel) at ((face * r + y) * r + x) * 3 + c.
// Faces follow the OpenGL cube-map convention (+X, -X, +Y, -Y, +Z, -Z; see cube_coord).
//
// Filtering across faces: bilinear taps are clamped at a face's edge (no fetch from the neighbouring face),
// so a seam of at most half a texel of the level in use can show; at the coarse levels rough lookups see a
// per-face average. This is the documented price of a cheap per-face prefilter.
#include <cmath>

#include <glm/glm.hpp>

#include "core/compute/hd.h"

namespace goris::envmap {

using std::floor;
using std::log2;

template <class T> using Vec3 = glm::vec<3, T, glm::defaultp>;

constexpr int kMaxLevels = 16;

// A read-only view of an activated mip chain (pointers on the device of the kernels that read it).
template <class T>
struct CubeMipsT {
  const T* texels = nullptr;
  int resolution = 0;  // R, texels per face side at level 0
  int levels = 0;      // L
};

GORIS_HDI int level_res(int R, int k) { return R >> k; }
GORIS_HDI long long level_offset(int R, int k) {
  long long off = 0;
  for (int j = 0; j < k; ++j) off += 18ll * level_res(R, j) * level_res(R, j);
  return off;
}
GORIS_HDI long long chain_size(int R, int L) { return level_offset(R, L); }

// Direction -> face and (u, v) in [0, 1]^2 with the data needed for d(u, v)/d(direction).
template <class T>
struct CubeCoord {
  int face = 0;
  int s_axis = 0, t_axis = 0, m_axis = 0;  // u from d[s_axis], v from d[t_axis], major axis d[m_axis]
  T s_sign = 1, t_sign = 1, m_sign = 1;
  T sc = 0, tc = 0, ma = 1;  // signed s, t coordinates and |major|
  T u = 0, v = 0;
};

template <class T>
GORIS_HDI CubeCoord<T> cube_coord(const Vec3<T>& d) {
  CubeCoord<T> c;
  const T ax = d.x < 0 ? -d.x : d.x, ay = d.y < 0 ? -d.y : d.y, az = d.z < 0 ? -d.z : d.z;
  if (ax >= ay && ax >= az) {
    const bool pos = d.x >= 0;
    c.face = pos ? 0 : 1;
    c.m_axis = 0, c.s_axis = 2, c.t_axis = 1;
    c.s_sign = pos ? T(-1) : T(1), c.t_sign = T(-1), c.m_sign = pos ? T(1) : T(-1);
  } else if (ay >= az) {
    const bool pos = d.y >= 0;
    c.face = pos ? 2 : 3;
    c.m_axis = 1, c.s_axis = 0, c.t_axis = 2;
    c.s_sign = T(1), c.t_sign = pos ? T(1) : T(-1), c.m_sign = pos ? T(1) : T(-1);
  } else {
    const bool pos = d.z >= 0;
    c.face = pos ? 4 : 5;
    c.m_axis = 2, c.s_axis = 0, c.t_axis = 1;
    c.s_sign = pos ? T(1) : T(-1), c.t_sign = T(-1), c.m_sign = pos ? T(1) : T(-1);
  }
  c.ma = c.m_sign * d[c.m_axis];
  c.sc = c.s_sign * d[c.s_axis];
  c.tc = c.t_sign * d[c.t_axis];
  c.u = T(0.5) * (c.sc / c.ma + T(1));
  c.v = T(0.5) * (c.tc / c.ma + T(1));
  return c;
}

// dL/d(direction) given dL/du and dL/dv (the face is held fixed: it changes only on measure-zero seams).
template <class T>
GORIS_HDI Vec3<T> cube_coord_vjp(const CubeCoord<T>& c, T du, T dv) {
  Vec3<T> g(T(0));
  const T inv = T(0.5) / c.ma;
  g[c.s_axis] += du * inv * c.s_sign;
  g[c.t_axis] += dv * inv * c.t_sign;
  g[c.m_axis] -= (du * c.sc + dv * c.tc) * inv / c.ma * c.m_sign;
  return g;
}

// Roughness -> continuous mip level. A level-k texel spans about 2 / (R >> k) radians and the [1 3 3 1]
// pyramid gives it a blur of about half that, so level log2(sigma * R) has angular spread sigma. The GGX
// reflected lobe with alpha = r^2 spreads about alpha, hence level = log2(r^2 R), clamped to the chain
// (r = 1 reaches the 1x1 level of a full chain). Returns the level and writes d level / d roughness.
template <class T>
GORIS_HDI T roughness_to_level(T roughness, int R, int L, T* dlevel_dr) {
  *dlevel_dr = T(0);
  const T r = roughness < T(0) ? T(0) : (roughness > T(1) ? T(1) : roughness);
  const T x = r * r * T(R);
  if (!(x > T(1))) return T(0);
  const T level = log2(x);
  if (level >= T(L - 1)) return T(L - 1);
  if (roughness > T(0) && roughness < T(1)) *dlevel_dr = T(2) / (r * T(0.6931471805599453));
  return level;
}

// Bilinear sample of one face of one level at (u, v); taps clamped at the face edges.
template <class T>
struct Bilinear {
  long long idx[4];  // texel offsets (first channel) of (y0,x0), (y0,x1), (y1,x0), (y1,x1)
  T w[4];
  T fx, fy;
  int res;
};

template <class T>
GORIS_HDI Bilinear<T> bilinear_taps(int R, int k, int face, T u, T v) {
  Bilinear<T> b;
  const int r = level_res(R, k);
  b.res = r;
  const T x = u * T(r) - T(0.5), y = v * T(r) - T(0.5);
  const T x0f = floor(x), y0f = floor(y);
  b.fx = x - x0f;
  b.fy = y - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  auto cl = [r](int i) { return i < 0 ? 0 : (i > r - 1 ? r - 1 : i); };
  const int xs[2] = {cl(x0), cl(x0 + 1)}, ys[2] = {cl(y0), cl(y0 + 1)};
  const long long base = level_offset(R, k) + 3ll * face * r * r;
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) b.idx[a * 2 + c] = base + 3ll * (ys[a] * r + xs[c]);
  b.w[0] = (T(1) - b.fy) * (T(1) - b.fx);
  b.w[1] = (T(1) - b.fy) * b.fx;
  b.w[2] = b.fy * (T(1) - b.fx);
  b.w[3] = b.fy * b.fx;
  return b;
}

template <class T>
GORIS_HDI Vec3<T> texel(const T* t, long long i) { return Vec3<T>(t[i], t[i + 1], t[i + 2]); }

template <class T>
GORIS_HDI Vec3<T> bilinear_value(const T* t, const Bilinear<T>& b) {
  Vec3<T> c(T(0));
  for (int q = 0; q < 4; ++q) c += b.w[q] * texel(t, b.idx[q]);
  return c;
}

// d value / du and d value / dv of a bilinear sample (per channel).
template <class T>
GORIS_HDI void bilinear_uv_grad(const T* t, const Bilinear<T>& b, Vec3<T>* dvalue_du, Vec3<T>* dvalue_dv) {
  const Vec3<T> t00 = texel(t, b.idx[0]), t01 = texel(t, b.idx[1]), t10 = texel(t, b.idx[2]), t11 = texel(t, b.idx[3]);
  *dvalue_du = ((T(1) - b.fy) * (t01 - t00) + b.fy * (t11 - t10)) * T(b.res);
  *dvalue_dv = ((T(1) - b.fx) * (t10 - t00) + b.fx * (t11 - t01)) * T(b.res);
}

// Everything a lookup needs to be replayed by its VJP.
template <class T>
struct LookupPlan {
  CubeCoord<T> coord;
  int l0 = 0, l1 = 0;
  T f = 0;         // weight of level l1
  T dlevel_dr = 0;
};

template <class T>
GORIS_HDI LookupPlan<T> plan_lookup(const CubeMipsT<T>& m, const Vec3<T>& dir, T roughness) {
  LookupPlan<T> p;
  p.coord = cube_coord(dir);
  const T level = roughness_to_level(roughness, m.resolution, m.levels, &p.dlevel_dr);
  p.l0 = int(floor(level));
  if (p.l0 > m.levels - 1) p.l0 = m.levels - 1;
  p.l1 = p.l0 + 1 < m.levels ? p.l0 + 1 : p.l0;
  p.f = p.l1 == p.l0 ? T(0) : level - T(p.l0);
  return p;
}

// Prefiltered radiance in direction `dir` (any non-zero length) for `roughness` (clamped to [0, 1]):
// bilinear within a level, linear between the two levels around the continuous level.
template <class T>
GORIS_HDI Vec3<T> cube_lookup(const CubeMipsT<T>& m, const Vec3<T>& dir, T roughness) {
  const LookupPlan<T> p = plan_lookup(m, dir, roughness);
  const CubeCoord<T>& c = p.coord;
  Vec3<T> out = (T(1) - p.f) * bilinear_value(m.texels, bilinear_taps(m.resolution, p.l0, c.face, c.u, c.v));
  if (p.f > T(0)) out += p.f * bilinear_value(m.texels, bilinear_taps(m.resolution, p.l1, c.face, c.u, c.v));
  return out;
}

// The texels a lookup reads: up to 8 taps (4 bilinear taps on each of the two levels), each with its texel
// offset and weight, so d lookup / d texel[idx[t] + ch] = w[t] per channel (taps may repeat a texel where
// they are clamped at a face edge; their weights then add).
template <class T>
struct LookupTaps {
  long long idx[8];
  T w[8];
  int n = 0;
};

template <class T>
GORIS_HDI LookupTaps<T> lookup_taps(const CubeMipsT<T>& m, const Vec3<T>& dir, T roughness) {
  const LookupPlan<T> p = plan_lookup(m, dir, roughness);
  const int lv[2] = {p.l0, p.l1};
  const T lw[2] = {T(1) - p.f, p.f};
  LookupTaps<T> taps;
  for (int s = 0; s < 2; ++s) {
    if (s == 1 && !(p.f > T(0))) break;
    const Bilinear<T> b = bilinear_taps(m.resolution, lv[s], p.coord.face, p.coord.u, p.coord.v);
    for (int q = 0; q < 4; ++q, ++taps.n) {
      taps.idx[taps.n] = b.idx[q];
      taps.w[taps.n] = lw[s] * b.w[q];
    }
  }
  return taps;
}

// VJP of cube_lookup for the direction and the roughness: dL/d(direction) and dL/d(roughness) through the
// out-parameters. The texels' gradient is lookup_taps' weights times dout, which callers sum in a fixed
// order (deferred_texel_grads.h).
template <class T>
GORIS_HDI void cube_lookup_vjp(const CubeMipsT<T>& m, const Vec3<T>& dir, T roughness, const Vec3<T>& dout,
                               Vec3<T>* ddir, T* droughness) {
  const LookupPlan<T> p = plan_lookup(m, dir, roughness);
  const CubeCoord<T>& c = p.coord;
  const int lv[2] = {p.l0, p.l1};
  const T lw[2] = {T(1) - p.f, p.f};
  Vec3<T> vals[2] = {Vec3<T>(T(0)), Vec3<T>(T(0))};
  T du = 0, dv = 0;
  for (int s = 0; s < 2; ++s) {
    if (s == 1 && !(p.f > T(0))) break;
    const Bilinear<T> b = bilinear_taps(m.resolution, lv[s], c.face, c.u, c.v);
    vals[s] = bilinear_value(m.texels, b);
    Vec3<T> gu, gv;
    bilinear_uv_grad(m.texels, b, &gu, &gv);
    du += lw[s] * glm::dot(dout, gu);
    dv += lw[s] * glm::dot(dout, gv);
  }
  *ddir = cube_coord_vjp(c, du, dv);
  *droughness = p.f > T(0) ? glm::dot(dout, vals[1] - vals[0]) * p.dlevel_dr : T(0);
}

}  // namespace goris::envmap
