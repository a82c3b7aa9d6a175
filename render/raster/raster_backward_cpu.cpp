// CPU backward pass. Each tile walks its Gaussians back to front (Gaussian-outer, pixel-inner, as the forward
// pass), rebuilding every pixel's transmittance from the stored final T and its last contributor as in
// 3DGS, and sums the tile's gradient for each Gaussian locally. The sum goes to the instance's own slot
// (unique per (tile, Gaussian)), so tiles never race and the result is deterministic; the shared
// backward_gaussians then adds each Gaussian's contiguous slots and applies the projection's VJP.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "render/raster/raster_cpu.h"
#include "render/raster/raster_pipeline.h"
#include "render/raster/stage_timer.h"
#include "render/raster/tile_loop.h"

namespace goris::raster {

namespace {

// dL/d(G-buffer) of one tile, channel-major [C][np].
template <class T>
struct PixelGrads {
  std::vector<T> dl;          // dL/d(channel c) per pixel
  std::vector<T> dalpha_out;  // dL/d(alpha image) - background . dL/dcolour
  std::vector<T> dmedian;
};

template <class T>
PixelGrads<T> load_pixel_grads(const RasterStateT<T>& st, const GBufferGradT<T>& go, const TileBox& box) {
  const int K = st.n_extras, C = kBaseChannels + K, np = box.w * box.h;
  const std::size_t P = std::size_t(st.camera.width) * std::size_t(st.camera.height);
  PixelGrads<T> pg;
  pg.dl.assign(std::size_t(np) * C, T(0));
  pg.dalpha_out.assign(np, T(0));
  pg.dmedian.assign(np, T(0));
  const T bg[3] = {T(st.settings.background.x), T(st.settings.background.y), T(st.settings.background.z)};
  auto plane = [&](int c) { return &pg.dl[std::size_t(c) * np]; };
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      const int p = y * box.w + x;
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

// For every pixel, with dl_c = dL/d(channel c) fixed, the gradient of the blend with respect to alpha_i is
//   dL/dalpha_i = T_i (V_i - S_i) - T_final / (1 - alpha_i) (background . dl_colour - dL/dA),
// where V_i = sum_c val_ic dl_c and S_i = sum_c (what is blended behind i, per unit transmittance) dl_c. Walking
// back to front, S_{i-1} = alpha_i V_i + (1 - alpha_i) S_i: one scalar per pixel carries all channels.
template <class T>
void backward_tile(int tile, const GaussiansT<T>& g, const RasterStateT<T>& st, const GBufferGradT<T>& go,
                   T* partials) {
  const TileBox box = tile_box(tile, st.tiles_x, st.camera.width, st.camera.height);
  const int K = st.n_extras, C = kBaseChannels + K, np = box.w * box.h, stride = grad_slot_stride(K);
  const std::uint32_t begin = st.tile_ranges[2 * tile], end = st.tile_ranges[2 * tile + 1];
  if (begin == end) return;
  const PixelGrads<T> pg = load_pixel_grads(st, go, box);
  std::vector<T> trans(np), t_final(np), behind(np, T(0));
  std::vector<std::uint32_t> n_contrib(np), median(np);
  std::uint32_t k_end = begin;
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      const int p = y * box.w + x;
      const std::size_t q = std::size_t(box.y0 + y) * std::size_t(st.camera.width) + std::size_t(box.x0 + x);
      trans[p] = t_final[p] = st.final_T[q];
      n_contrib[p] = st.n_contrib[q];
      median[p] = st.median_index[q];
      k_end = std::max(k_end, n_contrib[p]);
    }
  // Instances no pixel reached get zero partials.
  for (std::uint32_t k = k_end; k < end; ++k)
    std::fill_n(partials + std::size_t(st.sorted_slot[k]) * stride, stride, T(0));
  const T* dl[kMaxChannels];
  for (int c = 0; c < C; ++c) dl[c] = &pg.dl[std::size_t(c) * np];
  std::vector<T> dalpha_tf(np);  // (dL/dA - background . dL/dcolour) * T_final
  for (int p = 0; p < np; ++p) dalpha_tf[p] = pg.dalpha_out[p] * t_final[p];
  T val[kMaxChannels], gs[kGExtras + kMaxExtras];
  for (std::uint32_t k = k_end; k-- > begin;) {
    const SplatView<T> s = load_splat(st, st.sorted_gauss[k]);
    T* slot = partials + std::size_t(st.sorted_slot[k]) * stride;
    std::fill_n(gs, stride, T(0));
    PixelRange pr;
    AlphaEllipse<T> ell;
    if (!pixel_rows(s, box, ell, pr)) {
      std::copy_n(gs, stride, slot);
      continue;
    }
    splat_values(s, g, K, val);
    const T c0 = val[0], c1 = val[1], c2 = val[2], n0 = val[kChNormal], n1 = val[kChNormal + 1],
            n2 = val[kChNormal + 2];
    T gc0 = 0, gc1 = 0, gc2 = 0, gn0 = 0, gn1 = 0, gn2 = 0;
    for (int y = pr.y0; y <= pr.y1; ++y) {
      const T py = T(y) + T(0.5);
      int x0, x1;
      if (!pixel_span(s, box, ell, py, x0, x1)) continue;
      const int row = (y - box.y0) * box.w - box.x0;
      for (int x = x0; x <= x1; ++x) {
        const int p = row + x;
        if (k >= n_contrib[p]) continue;
        const PixelHit<T> h = eval_hit(s.mean, s.conic, s.opacity, T(x) + T(0.5), py);
        if (h.alpha == T(0)) continue;
        const T one_minus = T(1) - h.alpha;
        const T inv = T(1) / one_minus;
        const T Ti = trans[p] * inv;
        trans[p] = Ti;
        const T w = h.alpha * Ti;
        const T z = plane_depth(s.depth, s.plane, h.dx, h.dy);
        const T d0 = dl[0][p], d1 = dl[1][p], d2 = dl[2][p], dz = dl[kChDepth][p], dn0 = dl[kChNormal][p],
                dn1 = dl[kChNormal + 1][p], dn2 = dl[kChNormal + 2][p];
        T V = c0 * d0 + c1 * d1 + c2 * d2 + z * dz + n0 * dn0 + n1 * dn1 + n2 * dn2;
        for (int e = 0; e < K; ++e) {
          V += val[kChExtras + e] * dl[kChExtras + e][p];
          gs[kGExtras + e] += w * dl[kChExtras + e][p];
        }
        const T dalpha = Ti * (V - behind[p]) + dalpha_tf[p] * inv;
        behind[p] = h.alpha * V + one_minus * behind[p];
        gc0 += w * d0;
        gc1 += w * d1;
        gc2 += w * d2;
        gn0 += w * dn0;
        gn1 += w * dn1;
        gn2 += w * dn2;
        // Depth on the plane: blended, and the median pixel's own.
        plane_depth_vjp(s.plane, h.dx, h.dy, w * dz + (k == median[p] ? pg.dmedian[p] : T(0)), gs);
        eval_hit_vjp(s.conic, s.opacity, h, dalpha, gs);
      }
    }
    gs[kGColor] = gc0, gs[kGColor + 1] = gc1, gs[kGColor + 2] = gc2;
    gs[kGNormal] = gn0, gs[kGNormal + 1] = gn1, gs[kGNormal + 2] = gn2;
    std::copy_n(gs, stride, slot);
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
  tbb::parallel_for(0, n_tiles, [&](int tile) { backward_tile(tile, g, st, grad_out, partials.data()); });
  st.times.backward_blend = timer.lap();
  backward_gaussians(g, st, partials, out);
  st.times.backward_gaussians = timer.lap();
}

template void backward_cpu<float>(const GaussiansT<float>&, const RasterStateT<float>&, const GBufferGradT<float>&,
                                  const GaussianGradsT<float>&);
template void backward_cpu<double>(const GaussiansT<double>&, const RasterStateT<double>&,
                                   const GBufferGradT<double>&, const GaussianGradsT<double>&);

}  // namespace goris::raster
