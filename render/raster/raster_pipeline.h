#pragma once
// The device-generic stages of the rasterizer, written once with parallel_for / scans / sort_by_key and
// instantiated by the CPU driver (.cpp) and the CUDA driver (.cu):
//   preprocess          per Gaussian: projection, SH colour, depth plane, normal, radius, tile rectangle
//   bin_tiles           one (tile, depth) key per touched tile (exclusive scan for the slots), radix sort,
//                       tile ranges
//   backward_gaussians  per Gaussian: sum its per-tile partial gradients (contiguous slots), then the VJP
//                       of the projection and the SH colour into the parameter gradients (+=)
// Only the per-pixel blend differs between the backends (raster_forward_cpu.cpp, rasterizer_cuda.cu).
#include <bit>
#include <cstdint>
#include <cstring>

#include "core/compute/memory.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "render/math/sh.h"
#include "render/raster/blend.h"
#include "render/raster/projection.h"

namespace goris::raster {
GORIS_BACKEND_NAMESPACE_BEGIN

template <class T>
T read_element(const Buffer<T>& b, std::size_t i) {
  T v{};
  device_copy(&v, Device::CPU, b.data() + i, b.device(), sizeof(T));
  return v;
}

// Bit pattern of a depth, increasing with the depth (the low 31 bits of the sort key): positive floats
// order as their bits, and bit 31 (the sign) is 0. Depths <= 0 (only with a near plane <= 0) sort first.
constexpr int kDepthKeyBits = 31;
GORIS_HDI std::uint32_t depth_key(float z) {
  if (!(z > 0.f)) return 0u;
#if defined(__CUDA_ARCH__)
  return __float_as_uint(z);
#else
  return std::bit_cast<std::uint32_t>(z);
#endif
}

struct TileRect {
  int x0, y0, x1, y1;  // exclusive ends
};

// 3DGS's tile rectangle of a splat (the fixture's rule): [(int)((m - r) / 16), (int)((m + r + 15) / 16))
// clamped to the grid. A box that enters a tile by less than a pixel (m + r mod 16 < 1) skips that tile.
template <class T>
GORIS_HDI TileRect tile_rect(T mx, T my, T r, int tiles_x, int tiles_y) {
  const T ts = T(kTileSize);
  TileRect t;
  t.x0 = int(min(max((mx - r) / ts, T(0)), T(tiles_x)));
  t.y0 = int(min(max((my - r) / ts, T(0)), T(tiles_y)));
  t.x1 = int(min(max((mx + r + ts - T(1)) / ts, T(0)), T(tiles_x)));
  t.y1 = int(min(max((my + r + ts - T(1)) / ts, T(0)), T(tiles_y)));
  return t;
}

// Allocates the per-Gaussian state and runs the projection. counts[i] = tiles touched by Gaussian i.
template <class T>
void preprocess(const GaussiansT<T>& g, const Camera& cam, const RasterSettings& settings, Device dev,
                RasterStateT<T>& st, Buffer<std::uint32_t>& counts) {
  const std::size_t n = std::size_t(g.count);
  st.camera = cam;
  st.settings = settings;
  st.device = dev;
  st.count = g.count;
  st.sh_degree = g.sh_degree;
  st.n_extras = g.n_extras;
  st.tiles_x = (cam.width + kTileSize - 1) / kTileSize;
  st.tiles_y = (cam.height + kTileSize - 1) / kTileSize;
  st.radii = Buffer<std::int32_t>(n, dev);
  st.means2d = Buffer<T>(2 * n, dev);
  st.conics = Buffer<T>(3 * n, dev);
  st.opacities = Buffer<T>(n, dev);
  st.colors = Buffer<T>(3 * n, dev);
  st.depths = Buffer<T>(n, dev);
  st.depth_planes = Buffer<T>(2 * n, dev);
  st.normals = Buffer<T>(3 * n, dev);
  st.packed = Buffer<T>(kPackedStride * n, dev);
  st.offsets = Buffer<std::uint32_t>(n, dev);
  st.tile_rects = Buffer<std::int32_t>(4 * n, dev);
  counts = Buffer<std::uint32_t>(n, dev);

  const ProjectionParams<T> P = make_projection_params<T>(cam, settings);
  const int tiles_x = st.tiles_x, tiles_y = st.tiles_y;
  std::int32_t* radii = st.radii.data();
  T *m2 = st.means2d.data(), *con = st.conics.data(), *op = st.opacities.data(), *col = st.colors.data();
  T *dep = st.depths.data(), *pl = st.depth_planes.data(), *nor = st.normals.data(), *pk = st.packed.data();
  std::int32_t* rects = st.tile_rects.data();
  std::uint32_t* cnt = counts.data();
  parallel_for(dev, n, [=] GORIS_HD(std::size_t idx) {
    const int i = int(idx);
    radii[i] = 0;
    cnt[i] = 0;
    for (int k = 0; k < kPackedStride; ++k) pk[kPackedStride * std::size_t(i) + k] = T(0);
    for (int k = 0; k < 4; ++k) rects[4 * i + k] = 0;
    m2[2 * i] = m2[2 * i + 1] = op[i] = dep[i] = pl[2 * i] = pl[2 * i + 1] = T(0);
    for (int k = 0; k < 3; ++k) con[3 * i + k] = col[3 * i + k] = nor[3 * i + k] = T(0);
    const GaussianParams<T> gp = load_gaussian(g, i);
    Splat<T> s;
    ProjectionInternals<T> in;
    if (!project_gaussian(gp, P, s, in)) return;
    const int r = splat_radius(in, P.filter2d_var);
    const T rr = T(r);
    if (r <= 0 || s.mean2d.x + rr <= T(0) || s.mean2d.x - rr >= T(P.width) || s.mean2d.y + rr <= T(0) ||
        s.mean2d.y - rr >= T(P.height))
      return;
    const TileRect tr = tile_rect(s.mean2d.x, s.mean2d.y, rr, tiles_x, tiles_y);
    const int x0 = tr.x0, y0 = tr.y0, x1 = tr.x1, y1 = tr.y1;
    if (x1 <= x0 || y1 <= y0) return;
    radii[i] = r;
    cnt[i] = std::uint32_t((x1 - x0) * (y1 - y0));
    rects[4 * i] = x0, rects[4 * i + 1] = y0, rects[4 * i + 2] = x1, rects[4 * i + 3] = y1;
    m2[2 * i] = s.mean2d.x, m2[2 * i + 1] = s.mean2d.y;
    con[3 * i] = s.conic.x, con[3 * i + 1] = s.conic.y, con[3 * i + 2] = s.conic.z;
    op[i] = s.opacity;
    dep[i] = s.depth;
    pl[2 * i] = s.plane.x, pl[2 * i + 1] = s.plane.y;
    nor[3 * i] = s.normal.x, nor[3 * i + 1] = s.normal.y, nor[3 * i + 2] = s.normal.z;
    const Vec3<T> c = sh_color<T>(g.sh_degree, g.sh + 48 * std::size_t(i), gp.mean, P.center);
    col[3 * i] = c.x, col[3 * i + 1] = c.y, col[3 * i + 2] = c.z;
    T* q = pk + kPackedStride * std::size_t(i);
    q[kPkMean] = s.mean2d.x, q[kPkMean + 1] = s.mean2d.y;
    q[kPkConic] = s.conic.x, q[kPkConic + 1] = s.conic.y, q[kPkConic + 2] = s.conic.z;
    q[kPkOpacity] = s.opacity, q[kPkDepth] = s.depth;
    q[kPkPlane] = s.plane.x, q[kPkPlane + 1] = s.plane.y;
    q[kPkColor] = c.x, q[kPkColor + 1] = c.y, q[kPkColor + 2] = c.z;
    q[kPkNormal] = s.normal.x, q[kPkNormal + 1] = s.normal.y, q[kPkNormal + 2] = s.normal.z;
    q[kPkTwoL] = alpha_two_L(s.opacity);
  });
}

// Duplicates each visible Gaussian once per touched tile, sorts the instances by (tile, depth) and finds
// each tile's range. Instance slots of Gaussian i are offsets[i] .. offsets[i] + counts[i] - 1.
template <class T>
void bin_tiles(RasterStateT<T>& st, const Buffer<std::uint32_t>& counts) {
  const Device dev = st.device;
  const std::size_t n = std::size_t(st.count);
  const std::size_t n_tiles = std::size_t(st.tiles_x) * std::size_t(st.tiles_y);
  exclusive_scan(counts, st.offsets);
  st.n_instances = n ? std::size_t(read_element(st.offsets, n - 1)) + read_element(counts, n - 1) : 0;
  const std::size_t m = st.n_instances;
  Buffer<std::uint64_t> keys(m, dev);
  Buffer<std::uint32_t> slots(m, dev);
  Buffer<std::uint32_t> slot_gauss(m, dev);
  st.sorted_gauss = Buffer<std::uint32_t>(m, dev);
  st.tile_ranges = Buffer<std::uint32_t>(2 * n_tiles, dev);
  st.tile_ranges.fill_zero();
  {
    const std::uint32_t* off = st.offsets.data();
    const std::int32_t* rects = st.tile_rects.data();
    const std::int32_t* radii = st.radii.data();
    const T* dep = st.depths.data();
    std::uint64_t* k = keys.data();
    std::uint32_t *sl = slots.data(), *sg = slot_gauss.data();
    const int tiles_x = st.tiles_x;
    parallel_for(dev, n, [=] GORIS_HD(std::size_t i) {
      if (radii[i] == 0) return;
      std::uint32_t o = off[i];
      const std::uint64_t zbits = depth_key(float(dep[i]));
      for (int ty = rects[4 * i + 1]; ty < rects[4 * i + 3]; ++ty)
        for (int tx = rects[4 * i]; tx < rects[4 * i + 2]; ++tx, ++o) {
          k[o] = (std::uint64_t(ty * tiles_x + tx) << kDepthKeyBits) | zbits;
          sl[o] = o;
          sg[o] = std::uint32_t(i);
        }
    });
  }
  // Only the bits the keys use: tile indices < n_tiles, 31 depth bits (e.g. 39 bits, 5 passes, for 256 tiles).
  sort_by_key(keys, slots, kDepthKeyBits + int(std::bit_width(n_tiles - 1)));
  st.sorted_slot = std::move(slots);
  {
    const std::uint64_t* k = keys.data();
    const std::uint32_t *sl = st.sorted_slot.data(), *sg = slot_gauss.data();
    std::uint32_t *out = st.sorted_gauss.data(), *ranges = st.tile_ranges.data();
    parallel_for(dev, m, [=] GORIS_HD(std::size_t j) {
      out[j] = sg[sl[j]];
      const std::uint32_t tile = std::uint32_t(k[j] >> kDepthKeyBits);
      if (j == 0 || std::uint32_t(k[j - 1] >> kDepthKeyBits) != tile) ranges[2 * tile] = std::uint32_t(j);
      if (j + 1 == m || std::uint32_t(k[j + 1] >> kDepthKeyBits) != tile) ranges[2 * tile + 1] = std::uint32_t(j + 1);
    });
  }
}

// Sums each Gaussian's per-tile partial gradients (slots of grad_slot_stride(K) values, see blend.h) and
// back-propagates them through the projection and the SH colour into `out` (+=).
template <class T>
void backward_gaussians(const GaussiansT<T>& g, const RasterStateT<T>& st, const Buffer<T>& partials,
                        const GaussianGradsT<T>& out) {
  const ProjectionParams<T> P = make_projection_params<T>(st.camera, st.settings);
  const int K = st.n_extras, stride = grad_slot_stride(K);
  const std::int32_t *radii = st.radii.data(), *rects = st.tile_rects.data();
  const std::uint32_t* off = st.offsets.data();
  const T *part = partials.data(), *col = st.colors.data();
  parallel_for(st.device, std::size_t(st.count), [=] GORIS_HD(std::size_t idx) {
    const int i = int(idx);
    if (radii[i] == 0) return;
    T sum[kGExtras + kMaxExtras];
    for (int c = 0; c < stride; ++c) sum[c] = T(0);
    const std::size_t n_slots = std::size_t((rects[4 * i + 2] - rects[4 * i]) * (rects[4 * i + 3] - rects[4 * i + 1]));
    for (std::size_t s = 0; s < n_slots; ++s) {
      const T* p = part + (std::size_t(off[i]) + s) * std::size_t(stride);
      for (int c = 0; c < stride; ++c) sum[c] += p[c];
    }
    // A Gaussian no pixel passed a gradient to (hidden behind others, or outside every pixel's alpha
    // threshold: often a large share of them) adds nothing: skip its projection VJP.
    bool zero = true;
    for (int c = 0; c < stride; ++c) zero = zero && sum[c] == T(0);
    if (zero) return;
    if (out.extras)
      for (int e = 0; e < K; ++e) out.extras[std::size_t(i) * K + e] += sum[kGExtras + e];
    if (out.mean2d_grad_norm) out.mean2d_grad_norm[i] += sqrt(sum[kGMean] * sum[kGMean] + sum[kGMean + 1] * sum[kGMean + 1]);

    const GaussianParams<T> gp = load_gaussian(g, i);
    Splat<T> s;
    ProjectionInternals<T> in;
    project_gaussian(gp, P, s, in);
    SplatGrad<T> d;
    d.mean2d = Vec2<T>(sum[kGMean], sum[kGMean + 1]);
    d.conic = Vec3<T>(sum[kGConic], sum[kGConic + 1], sum[kGConic + 2]);
    d.opacity = sum[kGOpacity];
    d.depth = sum[kGDepth];
    d.plane = Vec2<T>(sum[kGPlane], sum[kGPlane + 1]);
    d.normal = Vec3<T>(sum[kGNormal], sum[kGNormal + 1], sum[kGNormal + 2]);
    const GaussianParamGrad<T> pg = project_gaussian_vjp(gp, P, s, in, d);
    const Vec3<T> color(col[3 * i], col[3 * i + 1], col[3 * i + 2]);
    const Vec3<T> dcolor(sum[kGColor], sum[kGColor + 1], sum[kGColor + 2]);
    const Vec3<T> dmean_sh = sh_color_vjp<T>(g.sh_degree, g.sh + 48 * std::size_t(i), gp.mean, P.center, color, dcolor,
                                             out.sh ? out.sh + 48 * std::size_t(i) : nullptr);
    if (out.positions)
      for (int k = 0; k < 3; ++k) out.positions[3 * i + k] += pg.mean[k] + dmean_sh[k];
    if (out.log_scales)
      for (int k = 0; k < 3; ++k) out.log_scales[3 * i + k] += pg.log_scale[k];
    if (out.rotations)
      for (int k = 0; k < 4; ++k) out.rotations[4 * i + k] += pg.quat[k];
    if (out.opacity_logits) out.opacity_logits[i] += pg.opacity_logit;
  });
}

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris::raster
