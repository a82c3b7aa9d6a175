// CPU forward pass: the shared preprocess and tile binning (raster_pipeline.h), then every 16x16 tile
// blended in parallel. Inside a tile the loop runs Gaussian-outer, pixel-inner over the part of the tile
// where the Gaussian can reach alpha >= 1/255 and whose pixels are not yet saturated (bit masks per row),
// a few pixels of a row at a time in SIMD lanes; the per-pixel maths (blend.h) is the one the CUDA kernel
// uses.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "core/compute/kernel_profile.h"
#include "render/raster/lane_hit_cpu.h"
#include "render/raster/lanes_cpu.h"
#include "render/raster/raster_cpu.h"
#include "render/raster/raster_pipeline.h"
#include "render/raster/stage_timer.h"
#include "render/raster/tile_loop.h"

namespace goris::raster {

namespace {

// Per-pixel state of a tile, channel-major so that a row of pixels is contiguous.
template <class T>
struct ForwardTile {
  std::vector<T> trans, acc, med_depth;
  std::vector<std::uint32_t> last, median;
  std::uint32_t live[kTileSize] = {};  // columns of each row still taking Gaussians (T above T_min)
  int live_rows = 0;
  T* channel(int c) { return &acc[std::size_t(c) * kTilePixels]; }
};

// One Gaussian over one group of N pixels of a row (lanes = columns lx0 .. lx0 + N - 1, `cols` the ones in
// its alpha span): the rule of eval_hit and the blend of the scalar 3DGS loop, lane by lane.
template <class T>
void blend_lanes(const SplatView<T>& s, const T* val, int K, std::uint32_t k, int ly, int lx0, unsigned cols, T px0,
                 T py, ForwardTile<T>& t) {
  using V = LaneV<T>;
  using M = LaneM<T>;
  const int p = ly * kTileSize + lx0;
  const LaneHit<T> h = lane_hit(s, px0, py, cols);
  M m = h.m;
  if (!lane_bits<T>(m)) return;
  const V &dx = h.dx, &dy = h.dy, &alpha = h.alpha;
  const V Tp = lane_load(&t.trans[p]);
  const V test_T = Tp * (T(1) - alpha);
  const unsigned stop = lane_bits<T>(m & (test_T < BlendConst<T>::T_min));
  if (stop) {
    t.live[ly] &= ~(stop << lx0);
    if (!t.live[ly]) --t.live_rows;
    m &= ~lane_mask<T>(stop);
  }
  const unsigned blend = lane_bits<T>(m);
  if (!blend) return;
  const V w = lane_select(m, alpha * Tp, V{});
  const V z = plane_depth(s.depth, s.plane, dx, dy);
  auto add = [&](int c, T v) {
    T* a = t.channel(c) + p;
    lane_store(a, lane_load(a) + w * v);
  };
  add(0, val[0]);
  add(1, val[1]);
  add(2, val[2]);
  {
    T* a = t.channel(kChDepth) + p;
    lane_store(a, lane_load(a) + w * z);
  }
  add(kChNormal, val[kChNormal]);
  add(kChNormal + 1, val[kChNormal + 1]);
  add(kChNormal + 2, val[kChNormal + 2]);
  for (int e = 0; e < K; ++e) add(kChExtras + e, val[kChExtras + e]);
  lane_store(&t.trans[p], lane_select(m, test_T, Tp));
  const M med = m & (Tp > T(0.5));
  lane_store(&t.med_depth[p], lane_select(med, z, lane_load(&t.med_depth[p])));
  lane_store_where<T>(&t.median[p], med, k);
  lane_store_where<T>(&t.last[p], m, k + 1);
}

template <class T>
void blend_tile(int tile, const GaussiansT<T>& g, RasterStateT<T>& st, GBufferT<T>& out) {
  constexpr int N = Lanes<T>::N;
  const TileBox box = tile_box(tile, st.tiles_x, st.camera.width, st.camera.height);
  const int K = st.n_extras, C = kBaseChannels + K;
  const std::uint32_t begin = st.tile_ranges[2 * tile], end = st.tile_ranges[2 * tile + 1];
  const T* const packed = st.packed.data();
  const std::uint32_t* const sorted = st.sorted_gauss.data();
  ForwardTile<T> t;
  t.trans.assign(kTilePixels, T(1));
  t.acc.assign(std::size_t(C) * kTilePixels, T(0));
  t.med_depth.assign(kTilePixels, T(0));
  t.last.assign(kTilePixels, begin);
  t.median.assign(kTilePixels, kNoContributor);
  for (int y = 0; y < box.h; ++y) t.live[y] = bit_range(0, box.w - 1);
  t.live_rows = box.h;
  T val[kMaxChannels];
  using Groups = GroupList<N>;
  Groups groups;
  for (std::uint32_t k = begin; k < std::min(end, begin + kPrefetchAhead); ++k) prefetch_splat(packed, g, K, sorted[k]);
  for (std::uint32_t k = begin; k < end && t.live_rows > 0; ++k) {
    if (k + kPrefetchAhead < end) prefetch_splat(packed, g, K, sorted[k + kPrefetchAhead]);
    const SplatView<T> s = load_splat(packed, sorted[k]);
    PixelRange pr;
    AlphaEllipse<T> ell;
    if (!pixel_rows(s, box, ell, pr)) continue;
    std::uint32_t live = 0;  // every pixel of its rows saturated: skip the spans
    for (int ly = pr.y0 - box.y0; ly <= pr.y1 - box.y0; ++ly) live |= t.live[ly];
    if (!live) continue;
    splat_values(s, g, K, val);
    RowMasks cols;
    span_masks(s, box, ell, pr, cols);
    groups.clear();
    for (int ly = pr.y0 - box.y0; ly <= pr.y1 - box.y0; ++ly) {
      cols[ly] &= t.live[ly];
      groups.add_row(ly, cols[ly]);
    }
    for (int i = 0; i < groups.size; ++i) {
      const int ly = groups.entry[i] / Groups::kGroups, lx = groups.entry[i] % Groups::kGroups * N;
      const unsigned lanes = (cols[ly] >> lx) & ((1u << N) - 1);
      blend_lanes(s, val, K, k, ly, lx, lanes, T(box.x0 + lx) + T(0.5), T(box.y0 + ly) + T(0.5), t);
    }
  }
  const std::size_t P = out.pixels();
  const T bg[3] = {T(st.settings.background.x), T(st.settings.background.y), T(st.settings.background.z)};
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      const int p = y * kTileSize + x;
      const std::size_t q = std::size_t(box.y0 + y) * std::size_t(st.camera.width) + std::size_t(box.x0 + x);
      for (int c = 0; c < 3; ++c) out.color[c * P + q] = t.channel(c)[p] + t.trans[p] * bg[c];
      out.alpha[q] = T(1) - t.trans[p];
      out.depth[q] = t.channel(kChDepth)[p];
      out.median_depth[q] = t.med_depth[p];
      for (int c = 0; c < 3; ++c) out.normal[c * P + q] = t.channel(kChNormal + c)[p];
      for (int e = 0; e < K; ++e) out.extras[e * P + q] = t.channel(kChExtras + e)[p];
      st.final_T[q] = t.trans[p];
      st.n_contrib[q] = t.last[p];
      st.median_index[q] = t.median[p];
    }
}

}  // namespace

template <class T>
void forward_cpu(const GaussiansT<T>& g, const Camera& cam, const RasterSettings& settings, GBufferT<T>& out,
                 RasterStateT<T>& st) {
  validate_inputs(g, cam);
  StageTimer timer(settings.profile, Device::CPU);
  Buffer<std::uint32_t> counts;
  preprocess(g, cam, settings, Device::CPU, st, counts);
  st.times.preprocess = timer.lap();
  bin_tiles(st, counts);
  st.times.binning = timer.lap();
  const std::size_t P = std::size_t(cam.width) * std::size_t(cam.height);
  out.width = cam.width;
  out.height = cam.height;
  out.n_extras = g.n_extras;
  out.color = Buffer<T>(3 * P);
  out.alpha = Buffer<T>(P);
  out.depth = Buffer<T>(P);
  out.median_depth = Buffer<T>(P);
  out.normal = Buffer<T>(3 * P);
  out.extras = Buffer<T>(std::size_t(g.n_extras) * P);
  st.final_T = Buffer<T>(P);
  st.n_contrib = Buffer<std::uint32_t>(P);
  st.median_index = Buffer<std::uint32_t>(P);
  const int n_tiles = st.tiles_x * st.tiles_y;
  {
    kernel_profile::Scope scope(Device::CPU);
    tbb::parallel_for(0, n_tiles, [&](int tile) { blend_tile(tile, g, st, out); });
  }
  st.times.blend = timer.lap();
}

template void forward_cpu<float>(const GaussiansT<float>&, const Camera&, const RasterSettings&, GBufferT<float>&,
                                 RasterStateT<float>&);
template void forward_cpu<double>(const GaussiansT<double>&, const Camera&, const RasterSettings&,
                                  GBufferT<double>&, RasterStateT<double>&);

}  // namespace goris::raster
