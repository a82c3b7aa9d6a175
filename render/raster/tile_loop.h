#pragma once
// Helpers of the CPU tile loops (forward and backward): a tile's pixel box, one Gaussian's screen-space data
// gathered from the state, and the pixels of a tile where that Gaussian can pass the alpha threshold.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "render/raster/blend.h"
#include "render/raster/raster_types.h"

namespace goris::raster {

struct TileBox {
  int x0, y0, w, h;  // first pixel and size (smaller at the right and bottom borders)
};

inline TileBox tile_box(int tile, int tiles_x, int width, int height) {
  TileBox b;
  b.x0 = (tile % tiles_x) * kTileSize;
  b.y0 = (tile / tiles_x) * kTileSize;
  b.w = std::min(kTileSize, width - b.x0);
  b.h = std::min(kTileSize, height - b.y0);
  return b;
}

template <class T>
struct SplatView {
  std::uint32_t id;
  Vec2<T> mean;
  Vec3<T> conic;
  T opacity, depth;
  Vec2<T> plane;
  const T* color;
  const T* normal;
};

template <class T>
SplatView<T> load_splat(const RasterStateT<T>& st, std::uint32_t i) {
  const T* q = &st.packed[kPackedStride * std::size_t(i)];
  SplatView<T> s;
  s.id = i;
  s.mean = Vec2<T>(q[kPkMean], q[kPkMean + 1]);
  s.conic = Vec3<T>(q[kPkConic], q[kPkConic + 1], q[kPkConic + 2]);
  s.opacity = q[kPkOpacity];
  s.depth = q[kPkDepth];
  s.plane = Vec2<T>(q[kPkPlane], q[kPkPlane + 1]);
  s.color = q + kPkColor;
  s.normal = q + kPkNormal;
  return s;
}

// The blended channel values of a splat (depth, which varies per pixel, is filled in by the caller).
template <class T>
void splat_values(const SplatView<T>& s, const GaussiansT<T>& g, int K, T* val) {
  for (int c = 0; c < 3; ++c) val[c] = s.color[c];
  val[kChDepth] = s.depth;
  for (int c = 0; c < 3; ++c) val[kChNormal + c] = s.normal[c];
  for (int e = 0; e < K; ++e) val[kChExtras + e] = g.extras[std::size_t(s.id) * K + e];
}

// ceil / floor of v clamped to [lo, hi], without libm calls (baseline x86-64 has no SSE4.1 rounding).
// Inside (lo, hi) int() truncates toward zero, then one comparison corrects it.
template <class T>
inline int clamped_ceil(T v, int lo, int hi) {
  if (!(v > T(lo))) return lo;
  if (!(v < T(hi))) return hi;
  const int c = int(v);
  return T(c) < v ? c + 1 : c;
}
template <class T>
inline int clamped_floor(T v, int lo, int hi) {
  if (!(v > T(lo))) return lo;
  if (!(v < T(hi))) return hi;
  const int c = int(v);
  return T(c) > v ? c - 1 : c;
}

// The part of a tile a splat can reach with alpha >= 1/255: rows [y0, y1], and per row a column span.
struct PixelRange {
  int y0, y1;
};

template <class T>
bool pixel_rows(const SplatView<T>& s, const TileBox& box, AlphaEllipse<T>& e, PixelRange& r) {
  if (!alpha_ellipse(s.conic, s.opacity, e)) return false;
  T yl, yh;
  alpha_rows(s.mean, s.conic, e, yl, yh);
  // Pixel y has its centre at y + 0.5.
  r.y0 = clamped_ceil(yl - T(0.5), box.y0, box.y0 + box.h);
  r.y1 = clamped_floor(yh - T(0.5), box.y0 - 1, box.y0 + box.h - 1);
  return r.y0 <= r.y1;
}

// Columns [x0, x1] of row y; false when empty.
template <class T>
bool pixel_span(const SplatView<T>& s, const TileBox& box, const AlphaEllipse<T>& e, T py, int& x0, int& x1) {
  T xl, xh;
  if (!alpha_span(s.mean, s.conic, e, py, xl, xh)) return false;
  x0 = clamped_ceil(xl - T(0.5), box.x0, box.x0 + box.w);
  x1 = clamped_floor(xh - T(0.5), box.x0 - 1, box.x0 + box.w - 1);
  return x0 <= x1;
}

}  // namespace goris::raster
