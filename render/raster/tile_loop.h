#pragma once
// Helpers of the CPU tile loops (forward and backward): a tile's pixel box, one Gaussian's screen-space data
// gathered from the packed state, and the pixels of a tile where that Gaussian can pass the alpha threshold,
// as one 16-bit column mask per row. Tile-local pixel p = ly * kTileSize + lx, the same for every tile (the
// columns and rows of border tiles that fall outside the image are never in a mask).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "render/raster/blend.h"
#include "render/raster/lanes_cpu.h"
#include "render/raster/raster_types.h"

namespace goris::raster {

constexpr int kTilePixels = kTileSize * kTileSize;
static_assert(kTileSize == 16, "column masks are 16-bit and row_mask_above reads 16 entries");
static_assert(std::endian::native == std::endian::little, "GroupList writes its entries as one 32-bit word");
// Instances ahead of the one being blended whose packed records are prefetched: the records are read in
// depth order, i.e. at random, and a tile spends long enough on each that a few ahead hide the miss.
constexpr int kPrefetchAhead = 4;

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

// Bits lo..hi (inclusive, 0 <= lo <= hi < 32) set.
inline std::uint32_t bit_range(int lo, int hi) {
  return (std::uint32_t(0xffffffffu) >> (31 - hi)) & (std::uint32_t(0xffffffffu) << lo);
}

inline void prefetch(const void* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

template <class T>
struct SplatView {
  std::uint32_t id;
  Vec2<T> mean;
  Vec3<T> conic;
  T opacity, depth, two_L;
  Vec2<T> plane;
  const T* color;
  const T* normal;
};

template <class T>
SplatView<T> load_splat(const T* packed, std::uint32_t i) {
  const T* q = packed + kPackedStride * std::size_t(i);
  SplatView<T> s;
  s.id = i;
  s.mean = Vec2<T>(q[kPkMean], q[kPkMean + 1]);
  s.conic = Vec3<T>(q[kPkConic], q[kPkConic + 1], q[kPkConic + 2]);
  s.opacity = q[kPkOpacity];
  s.depth = q[kPkDepth];
  s.two_L = q[kPkTwoL];
  s.plane = Vec2<T>(q[kPkPlane], q[kPkPlane + 1]);
  s.color = q + kPkColor;
  s.normal = q + kPkNormal;
  return s;
}

// Starts loading the packed record (and extras) of Gaussian i.
template <class T>
void prefetch_splat(const T* packed, const GaussiansT<T>& g, int K, std::uint32_t i) {
  prefetch(packed + kPackedStride * std::size_t(i));
  if (K > 0) prefetch(g.extras + std::size_t(i) * K);
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
  if (!alpha_ellipse(s.conic, s.two_L, e)) return false;
  T yl, yh;
  alpha_rows(s.mean, s.conic, e, yl, yh);
  // Pixel y has its centre at y + 0.5.
  r.y0 = clamped_ceil(yl - T(0.5), box.y0, box.y0 + box.h);
  r.y1 = clamped_floor(yh - T(0.5), box.y0 - 1, box.y0 + box.h - 1);
  return r.y0 <= r.y1;
}

// clamped_ceil / clamped_floor per lane.
template <class T>
LaneM<T> lane_clamped_ceil(LaneV<T> v, int lo, int hi) {
  const LaneM<T> above = v > T(lo), below = v < T(hi);
  const LaneV<T> vc = lane_select(above & below, v, lane_splat(T(lo)));
  LaneM<T> c = lane_trunc<T>(vc);
  c -= lane_float<T>(c) < vc;  // true is -1
  return lane_select(above, lane_select(below, c, LaneM<T>{} + hi), LaneM<T>{} + lo);
}
template <class T>
LaneM<T> lane_clamped_floor(LaneV<T> v, int lo, int hi) {
  const LaneM<T> above = v > T(lo), below = v < T(hi);
  const LaneV<T> vc = lane_select(above & below, v, lane_splat(T(lo)));
  LaneM<T> c = lane_trunc<T>(vc);
  c += lane_float<T>(c) > vc;
  return lane_select(above, lane_select(below, c, LaneM<T>{} + hi), LaneM<T>{} + lo);
}

// Column masks of a splat's rows: entries for kTileSize rows and the spare ones span_masks writes past the
// last row.
constexpr int kSpanSlack = 4;
using RowMasks = std::uint32_t[kTileSize + kSpanSlack];

// Column masks (tile-local columns) of rows pr.y0 .. pr.y1 into cols[y - box.y0]: alpha_span_q/_ends and the
// clamped rounding of the scalar rule, a few rows at a time in SIMD lanes (entries past pr.y1 up to the
// end of the last group of rows are overwritten too).
template <class T>
void span_masks(const SplatView<T>& s, const TileBox& box, const AlphaEllipse<T>& e, const PixelRange& pr,
                RowMasks& cols) {
  static_assert(Lanes<T>::N <= kSpanSlack);
  using V = LaneV<T>;
  using M = LaneM<T>;
  constexpr int N = Lanes<T>::N;
  if (e.unbounded) {
    for (int y = pr.y0; y <= pr.y1; ++y) cols[y - box.y0] = bit_range(0, box.w - 1);
    return;
  }
  for (int y = pr.y0; y <= pr.y1; y += N) {
    const V dy = s.mean.y - lane_iota(T(y) + T(0.5));
    const V q = alpha_span_q(s.conic, e, dy);
    const M hit = !(q < T(0));
    V xl, xh;
    alpha_span_ends(s.mean, s.conic, dy, lane_sqrt<T>(lane_select(hit, q, V{})), xl, xh);
    const M x0 = lane_clamped_ceil<T>(xl - T(0.5), box.x0, box.x0 + box.w) - box.x0;
    const M x1 = lane_clamped_floor<T>(xh - T(0.5), box.x0 - 1, box.x0 + box.w - 1) - box.x0;
    // Bits x0 .. x1 = 2^(x1 + 1) - 2^x0 (x0 <= 16, x1 + 1 <= 16 within the tile), 0 for empty spans.
    const M ok = hit & (x0 <= x1);
    const M bits = (lane_pow2<T>(lane_select(ok, x1 + 1, M{})) - lane_pow2<T>(lane_select(ok, x0, M{})));
    for (int j = 0; j < N; ++j) cols[y + j - box.y0] = std::uint32_t(bits[j]);
  }
}

// The groups of N neighbouring columns (lanes) of a splat's rows that hold a pixel to visit, listed first
// and then visited in one loop: a loop per row and per group would mispredict a branch at almost every
// row, as the spans and their widths vary from row to row.
template <int N>
struct GroupList {
  static constexpr int kGroups = kTileSize / N;  // per row
  // Entries ly * kGroups + group; kGroups spare entries for the branch-free append.
  std::uint8_t entry[kTileSize * kGroups + kGroups];
  int size = 0;

  void clear() { size = 0; }
  // Appends the groups of row ly that hold a bit of cols.
  void add_row(int ly, std::uint32_t cols) {
    unsigned any = 0;  // bit g: group g holds a bit
    if constexpr (kGroups == 4) {
      // OR each group of 4 into its lowest bit (0, 4, 8, 12), then move those to bits 12..15 by one product
      // (the shifts 12, 9, 6, 3 of 0x1248 send bit 4g to 12 + g, every other product bit elsewhere).
      std::uint32_t t = cols | cols >> 1;
      t = (t | t >> 2) & 0x1111u;
      any = (t * 0x1248u) >> 12 & 0xfu;
      // Write all four candidates, keep as many as there are groups: no branch per group.
      const std::uint32_t four = kOrder4[any] + std::uint32_t(ly * kGroups) * 0x01010101u;
      std::memcpy(&entry[size], &four, 4);
      size += kCount4[any];  // (std::popcount is a libgcc call on baseline x86-64)
    } else {
      for (int gi = 0; gi < kGroups; ++gi) any |= unsigned(((cols >> (gi * N)) & ((1u << N) - 1)) != 0) << gi;
      for (; any; any &= any - 1) entry[size++] = std::uint8_t(ly * kGroups + std::countr_zero(any));
    }
  }

  static constexpr std::uint8_t kCount4[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
  // kOrder4[m]: the set bits of the 4-bit mask m in increasing order, one per byte from the lowest (the
  // rest 0): four entries written at once, in memory order on a little-endian machine.
  static constexpr std::uint32_t kOrder4[16] = {
      0x00000000, 0x00000000, 0x00000001, 0x00000100, 0x00000002, 0x00000200, 0x00000201, 0x00020100,
      0x00000003, 0x00000300, 0x00000301, 0x00030100, 0x00000302, 0x00030200, 0x00030201, 0x03020100};
};

}  // namespace goris::raster
