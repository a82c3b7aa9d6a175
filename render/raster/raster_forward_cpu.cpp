// CPU forward pass: the shared preprocess and tile binning (raster_pipeline.h), then every 16x16 tile
// blended in parallel. Inside a tile the loop runs Gaussian-outer, pixel-inner over the part of the tile
// where the Gaussian can reach alpha >= 1/255; the per-pixel maths (blend.h) is the one the CUDA kernel uses.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "render/raster/raster_cpu.h"
#include "render/raster/raster_pipeline.h"
#include "render/raster/stage_timer.h"
#include "render/raster/tile_loop.h"

namespace goris::raster {

namespace {

template <class T>
void blend_tile(int tile, const GaussiansT<T>& g, RasterStateT<T>& st, GBufferT<T>& out) {
  const TileBox box = tile_box(tile, st.tiles_x, st.camera.width, st.camera.height);
  const int K = st.n_extras, C = kBaseChannels + K, np = box.w * box.h;
  const std::uint32_t begin = st.tile_ranges[2 * tile], end = st.tile_ranges[2 * tile + 1];
  // Per-pixel state, channel-major so that a row of pixels is contiguous.
  std::vector<T> trans(np, T(1)), acc(std::size_t(C) * np, T(0)), med_depth(np, T(0));
  std::vector<std::uint32_t> last(np, begin), median(np, kNoContributor);
  std::vector<unsigned char> done(np, 0);
  auto channel = [&](int c) { return &acc[std::size_t(c) * np]; };
  T* const a_c0 = channel(0);
  T* const a_c1 = channel(1);
  T* const a_c2 = channel(2);
  T* const a_z = channel(kChDepth);
  T* const a_n0 = channel(kChNormal);
  T* const a_n1 = channel(kChNormal + 1);
  T* const a_n2 = channel(kChNormal + 2);
  int n_done = 0;
  T val[kMaxChannels];
  for (std::uint32_t k = begin; k < end && n_done < np; ++k) {
    const SplatView<T> s = load_splat(st, st.sorted_gauss[k]);
    PixelRange pr;
    AlphaEllipse<T> ell;
    if (!pixel_rows(s, box, ell, pr)) continue;
    splat_values(s, g, K, val);
    const T c0 = val[0], c1 = val[1], c2 = val[2], n0 = val[kChNormal], n1 = val[kChNormal + 1],
            n2 = val[kChNormal + 2];
    for (int y = pr.y0; y <= pr.y1; ++y) {
      const T py = T(y) + T(0.5);
      int x0, x1;
      if (!pixel_span(s, box, ell, py, x0, x1)) continue;
      const int row = (y - box.y0) * box.w - box.x0;
      for (int x = x0; x <= x1; ++x) {
        const int p = row + x;
        if (done[p]) continue;
        const PixelHit<T> h = eval_hit(s.mean, s.conic, s.opacity, T(x) + T(0.5), py);
        const T alpha = h.alpha;
        if (alpha == T(0)) continue;
        const T Tp = trans[p];
        const T test_T = Tp * (T(1) - alpha);
        if (test_T < BlendConst<T>::T_min) {
          done[p] = 1;
          ++n_done;
          continue;
        }
        const T w = alpha * Tp;
        const T z = plane_depth(s.depth, s.plane, h.dx, h.dy);
        a_c0[p] += w * c0;
        a_c1[p] += w * c1;
        a_c2[p] += w * c2;
        a_z[p] += w * z;
        a_n0[p] += w * n0;
        a_n1[p] += w * n1;
        a_n2[p] += w * n2;
        for (int e = 0; e < K; ++e) channel(kChExtras + e)[p] += w * val[kChExtras + e];
        if (Tp > T(0.5)) {
          median[p] = k;
          med_depth[p] = z;
        }
        trans[p] = test_T;
        last[p] = k + 1;
      }
    }
  }
  const std::size_t P = out.pixels();
  const T bg[3] = {T(st.settings.background.x), T(st.settings.background.y), T(st.settings.background.z)};
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      const int p = y * box.w + x;
      const std::size_t q = std::size_t(box.y0 + y) * std::size_t(st.camera.width) + std::size_t(box.x0 + x);
      for (int c = 0; c < 3; ++c) out.color[c * P + q] = channel(c)[p] + trans[p] * bg[c];
      out.alpha[q] = T(1) - trans[p];
      out.depth[q] = a_z[p];
      out.median_depth[q] = med_depth[p];
      for (int c = 0; c < 3; ++c) out.normal[c * P + q] = channel(kChNormal + c)[p];
      for (int e = 0; e < K; ++e) out.extras[e * P + q] = channel(kChExtras + e)[p];
      st.final_T[q] = trans[p];
      st.n_contrib[q] = last[p];
      st.median_index[q] = median[p];
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
  tbb::parallel_for(0, n_tiles, [&](int tile) { blend_tile(tile, g, st, out); });
  st.times.blend = timer.lap();
}

template void forward_cpu<float>(const GaussiansT<float>&, const Camera&, const RasterSettings&, GBufferT<float>&,
                                 RasterStateT<float>&);
template void forward_cpu<double>(const GaussiansT<double>&, const Camera&, const RasterSettings&,
                                  GBufferT<double>&, RasterStateT<double>&);

}  // namespace goris::raster
