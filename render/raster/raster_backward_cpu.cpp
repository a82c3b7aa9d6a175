// CPU backward pass. Each tile walks its Gaussians back to front (Gaussian-outer, pixel-inner over the
// pixels in front of whose last contributor it lies, as the forward pass), rebuilding every pixel's
// transmittance from the stored final T and its last contributor as in 3DGS, and sums the tile's gradient
// for each Gaussian locally. The sum goes to the instance's own slot (unique per (tile, Gaussian)), so
// tiles never race and the result is deterministic; the shared backward_gaussians then adds each
// Gaussian's contiguous slots and applies the projection's VJP.
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

// dL/d(G-buffer) of one tile, channel-major [C][kTilePixels] (tile-local pixel indices).
template <class T>
struct PixelGrads {
  std::vector<T> dl;          // dL/d(channel c) per pixel
  std::vector<T> dalpha_out;  // dL/d(alpha image) - background . dL/dcolour
  std::vector<T> dmedian;
};

template <class T>
PixelGrads<T> load_pixel_grads(const RasterStateT<T>& st, const GBufferGradT<T>& go, const TileBox& box) {
  const int K = st.n_extras, C = kBaseChannels + K;
  const std::size_t P = std::size_t(st.camera.width) * std::size_t(st.camera.height);
  PixelGrads<T> pg;
  pg.dl.assign(std::size_t(kTilePixels) * C, T(0));
  pg.dalpha_out.assign(kTilePixels, T(0));
  pg.dmedian.assign(kTilePixels, T(0));
  const T bg[3] = {T(st.settings.background.x), T(st.settings.background.y), T(st.settings.background.z)};
  auto plane = [&](int c) { return &pg.dl[std::size_t(c) * kTilePixels]; };
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      const int p = y * kTileSize + x;
      const std::size_t q = std::size_t(box.y0 + y) * std::size_t(st.camera.width) + std::size_t(box.x0 + x);
      if (go.color)
        for (int c = 0; c < 3; ++c) {
          plane(c)[p] = go.color[c * P + q];
          pg.dalpha_out[p] -= bg[c] * plane(c)[p];
        }
      if (go.alpha) pg.dalpha_out[p] += go.alpha[q];
      if (go.depth) plane(kChDepth)[p] = go.depth[q];
      if (go.normal)
        for (int c = 0; c < 3; ++c) plane(kChNormal + c)[p] = go.normal[c * P + q];
      if (go.extras)
        for (int e = 0; e < K; ++e) plane(kChExtras + e)[p] = go.extras[e * P + q];
      if (go.median_depth) pg.dmedian[p] = go.median_depth[q];
    }
  return pg;
}

// Per-pixel state of a tile's backward walk (tile-local pixel indices).
template <class T>
struct BackwardTile {
  std::vector<T> trans, behind, dalpha_tf;
  std::vector<std::uint32_t> n_contrib, median;
  const T* dl[kMaxChannels];
  const T* dmedian;
};

// One Gaussian's per-tile gradient sums, per lane (summed over the lanes once the tile is done with it).
template <class T>
struct LaneGrads {
  HitMoments<LaneV<T>> hit;
  LaneV<T> color[3], normal[3], extras[kMaxExtras];
};

// For every pixel, with dl_c = dL/d(channel c) fixed, the gradient of the blend with respect to alpha_i is
//   dL/dalpha_i = T_i (V_i - S_i) - T_final / (1 - alpha_i) (background . dl_colour - dL/dA),
// where V_i = sum_c val_ic dl_c and S_i = sum_c (what is blended behind i, per unit transmittance) dl_c. Walking
// back to front, S_{i-1} = alpha_i V_i + (1 - alpha_i) S_i: one scalar per pixel carries all channels.
// One Gaussian (instance k) over one group of N pixels of a row; `cols` are the lanes it lies in front of
// the last contributor of, within its alpha span.
template <class T>
void backward_lanes(const SplatView<T>& s, const T* val, int K, std::uint32_t k, int ly, int lx0, unsigned cols,
                    T px0, T py, BackwardTile<T>& t, LaneGrads<T>& gr) {
  using V = LaneV<T>;
  using M = LaneM<T>;
  const int p = ly * kTileSize + lx0;
  const LaneHit<T> h = lane_hit(s, px0, py, cols);
  M m = h.m;
  if (!lane_bits<T>(m)) return;
  const V &dx = h.dx, &dy = h.dy, &G = h.G, &oG = h.oG, &alpha = h.alpha;
  const V one_minus = T(1) - alpha;
  const V inv = T(1) / one_minus;
  const V trans = lane_load(&t.trans[p]);
  const V Ti = trans * inv;
  lane_store(&t.trans[p], lane_select(m, Ti, trans));
  const V w = lane_select(m, alpha * Ti, V{});
  const V z = plane_depth(s.depth, s.plane, dx, dy);
  // Vs = sum_c val_c dl_c in channel order, and the channel gradients w dl_c, one channel at a time.
  V Vs{};
  auto channel = [&](int c, T v, V& grad) {
    const V d = lane_load(t.dl[c] + p);
    Vs += v * d;
    grad += w * d;
  };
  channel(0, val[0], gr.color[0]);
  channel(1, val[1], gr.color[1]);
  channel(2, val[2], gr.color[2]);
  const V dz = lane_load(t.dl[kChDepth] + p);
  Vs += z * dz;
  channel(kChNormal, val[kChNormal], gr.normal[0]);
  channel(kChNormal + 1, val[kChNormal + 1], gr.normal[1]);
  channel(kChNormal + 2, val[kChNormal + 2], gr.normal[2]);
  for (int e = 0; e < K; ++e) channel(kChExtras + e, val[kChExtras + e], gr.extras[e]);
  const V behind = lane_load(&t.behind[p]);
  const V dalpha = Ti * (Vs - behind) + lane_load(&t.dalpha_tf[p]) * inv;
  lane_store(&t.behind[p], lane_select(m, alpha * Vs + one_minus * behind, behind));
  // Depth on the plane: blended, and the median pixel's own.
  V gd = w * dz;
  const M med = m & lane_equal<T>(&t.median[p], k);
  if (lane_bits<T>(med)) gd += lane_select(med, lane_load(t.dmedian + p), V{});
  // No gradient through the 0.99 clamp (eval_hit_vjp).
  const M unclamped = m & ~(oG > BlendConst<T>::alpha_max);
  hit_moments_add(gr.hit, G, dx, dy, lane_select(unclamped, dalpha, V{}), gd);
}

template <class T>
void backward_tile(int tile, const GaussiansT<T>& g, const RasterStateT<T>& st, const GBufferGradT<T>& go,
                   T* partials) {
  constexpr int N = Lanes<T>::N;
  const TileBox box = tile_box(tile, st.tiles_x, st.camera.width, st.camera.height);
  const int K = st.n_extras, C = kBaseChannels + K, stride = grad_slot_stride(K);
  const std::uint32_t begin = st.tile_ranges[2 * tile], end = st.tile_ranges[2 * tile + 1];
  if (begin == end) return;
  const T* const packed = st.packed.data();
  const std::uint32_t *const sorted = st.sorted_gauss.data(), *const slots = st.sorted_slot.data();
  const PixelGrads<T> pg = load_pixel_grads(st, go, box);
  BackwardTile<T> t;
  t.trans.assign(kTilePixels, T(1));
  t.behind.assign(kTilePixels, T(0));
  t.dalpha_tf.assign(kTilePixels, T(0));
  // Pixels outside the image never contribute (n_contrib 0).
  t.n_contrib.assign(kTilePixels, 0);
  t.median.assign(kTilePixels, kNoContributor);
  // Columns of each row in front of whose last contributor the walk is (n_contrib > k), and the n_contrib
  // at which the next column joins: the masks change at most 16 times per row and tile.
  std::uint32_t front[kTileSize] = {}, row_end[kTileSize] = {};
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      const int p = y * kTileSize + x;
      const std::size_t q = std::size_t(box.y0 + y) * std::size_t(st.camera.width) + std::size_t(box.x0 + x);
      t.trans[p] = st.final_T[q];
      // (dL/dA - background . dL/dcolour) * T_final
      t.dalpha_tf[p] = pg.dalpha_out[p] * t.trans[p];
      t.n_contrib[p] = st.n_contrib[q];
      t.median[p] = st.median_index[q];
      row_end[y] = std::max(row_end[y], t.n_contrib[p]);
    }
  const std::uint32_t k_end = std::max(begin, *std::max_element(row_end, row_end + kTileSize));
  // Instances no pixel reached get zero partials.
  for (std::uint32_t k = k_end; k < end; ++k) std::fill_n(partials + std::size_t(slots[k]) * stride, stride, T(0));
  for (int c = 0; c < C; ++c) t.dl[c] = &pg.dl[std::size_t(c) * kTilePixels];
  t.dmedian = pg.dmedian.data();
  T val[kMaxChannels];
  LaneGrads<T> gr;
  using Groups = GroupList<N>;
  Groups groups;
  for (std::uint32_t i = 1; i <= std::uint32_t(kPrefetchAhead) && k_end >= begin + i; ++i)
    prefetch_splat(packed, g, K, sorted[k_end - i]);
  for (std::uint32_t k = k_end; k-- > begin;) {
    if (k >= begin + kPrefetchAhead) prefetch_splat(packed, g, K, sorted[k - kPrefetchAhead]);
    const SplatView<T> s = load_splat(packed, sorted[k]);
    T* slot = partials + std::size_t(slots[k]) * stride;
    PixelRange pr;
    AlphaEllipse<T> ell;
    groups.clear();
    RowMasks cols;
    if (pixel_rows(s, box, ell, pr)) {
      span_masks(s, box, ell, pr, cols);
      for (int ly = pr.y0 - box.y0; ly <= pr.y1 - box.y0; ++ly) {
        // Keep the pixels this instance lies in front of the last contributor of.
        const std::uint32_t* nc = &t.n_contrib[ly * kTileSize];
        if (k < row_end[ly]) {
          front[ly] = row_mask_above(nc, k);
          row_end[ly] = 0;
          for (int x = 0; x < kTileSize; ++x) row_end[ly] = std::max(row_end[ly], (front[ly] >> x & 1u) ? 0u : nc[x]);
        }
        cols[ly] &= front[ly];
        groups.add_row(ly, cols[ly]);
      }
    }
    if (groups.size == 0) {  // no pixel: a zero gradient
      std::fill_n(slot, stride, T(0));
      continue;
    }
    splat_values(s, g, K, val);
    gr.hit = HitMoments<LaneV<T>>{};
    for (int c = 0; c < 3; ++c) gr.color[c] = gr.normal[c] = LaneV<T>{};
    for (int e = 0; e < K; ++e) gr.extras[e] = LaneV<T>{};
    for (int i = 0; i < groups.size; ++i) {
      const int ly = groups.entry[i] / Groups::kGroups, lx = groups.entry[i] % Groups::kGroups * N;
      const unsigned lanes = (cols[ly] >> lx) & ((1u << N) - 1);
      backward_lanes(s, val, K, k, ly, lx, lanes, T(box.x0 + lx) + T(0.5), T(box.y0 + ly) + T(0.5), t, gr);
    }
    // The lanes' sums, in lane order.
    HitMoments<T> hit;
    hit.q = lane_sum<T>(gr.hit.q), hit.qx = lane_sum<T>(gr.hit.qx), hit.qy = lane_sum<T>(gr.hit.qy);
    hit.qxx = lane_sum<T>(gr.hit.qxx), hit.qxy = lane_sum<T>(gr.hit.qxy), hit.qyy = lane_sum<T>(gr.hit.qyy);
    hit.gd = lane_sum<T>(gr.hit.gd), hit.gdx = lane_sum<T>(gr.hit.gdx), hit.gdy = lane_sum<T>(gr.hit.gdy);
    T gs[kGExtras] = {};
    hit_moments_grad(hit, s.conic, s.opacity, s.plane, gs);
    for (int c = 0; c < 3; ++c) gs[kGColor + c] = lane_sum<T>(gr.color[c]), gs[kGNormal + c] = lane_sum<T>(gr.normal[c]);
    for (int c = 0; c < kGExtras; ++c) slot[c] = gs[c];
    for (int e = 0; e < K; ++e) slot[kGExtras + e] = lane_sum<T>(gr.extras[e]);
  }
}

}  // namespace

template <class T>
void backward_cpu(const GaussiansT<T>& g, const RasterStateT<T>& st, const GBufferGradT<T>& grad_out,
                  const GaussianGradsT<T>& out) {
  if (st.device != Device::CPU) throw Error("rasterizer", "backward_cpu was given a state that lives on CUDA");
  if (g.count != st.count || g.n_extras != st.n_extras || g.sh_degree != st.sh_degree)
    throw Error("rasterizer", "backward pass got a different Gaussian view than its forward pass");
  StageTimer timer(st.settings.profile, Device::CPU);
  const int stride = grad_slot_stride(st.n_extras);
  Buffer<T> partials(st.n_instances * std::size_t(stride));
  const int n_tiles = st.tiles_x * st.tiles_y;
  {
    kernel_profile::Scope scope(Device::CPU);
    tbb::parallel_for(0, n_tiles, [&](int tile) { backward_tile(tile, g, st, grad_out, partials.data()); });
  }
  st.times.backward_blend = timer.lap();
  backward_gaussians(g, st, partials, out);
  st.times.backward_gaussians = timer.lap();
}

template void backward_cpu<float>(const GaussiansT<float>&, const RasterStateT<float>&, const GBufferGradT<float>&,
                                  const GaussianGradsT<float>&);
template void backward_cpu<double>(const GaussiansT<double>&, const RasterStateT<double>&,
                                   const GBufferGradT<double>&, const GaussianGradsT<double>&);

}  // namespace goris::raster
