// CUDA driver of the rasterizer. Preprocess, binning (CUB radix sort through sort_by_key) and the
// per-Gaussian backward are the shared raster_pipeline.h stages on Device::CUDA; the blend is one thread
// per pixel and one 16x16 block per tile, with the tile's Gaussians staged through shared memory in batches
// as in 3DGS. The per-(pixel, Gaussian) maths is blend.h's, the same the CPU loops use.
#include <cuda_runtime.h>

#include "core/compute/cuda_check.h"
#include "core/compute/kernel_profile.h"
#include "render/raster/raster_cpu.h"
#include "render/raster/raster_pipeline.h"
#include "render/raster/rasterizer_cuda.h"
#include "render/raster/stage_timer.h"

namespace goris::raster {

namespace {

constexpr int kBlock = kTileSize * kTileSize;

struct BlendParams {
  const std::uint32_t* ranges;
  const std::uint32_t* sorted_gauss;
  const std::uint32_t* sorted_slot;
  const float* packed;
  const float* extras;
  int n_extras, width, height, tiles_x;
  float bg[3];
};

struct ForwardOut {
  float *color, *alpha, *depth, *median_depth, *normal, *extras, *final_T;
  std::uint32_t *n_contrib, *median_index;
};

// Stages one batch of the tile's Gaussians (packed records and extras) in shared memory.
__device__ void stage_batch(const BlendParams& p, std::uint32_t k, bool valid, float* s_pk, float* s_ex) {
  const int t = threadIdx.x;
  if (!valid) return;
  const std::uint32_t id = p.sorted_gauss[k];
  for (int c = 0; c < kPackedStride; ++c) s_pk[t * kPackedStride + c] = p.packed[std::size_t(id) * kPackedStride + c];
  for (int e = 0; e < p.n_extras; ++e) s_ex[t * kMaxExtras + e] = p.extras[std::size_t(id) * p.n_extras + e];
}

__global__ void __launch_bounds__(kBlock) blend_forward_kernel(BlendParams p, ForwardOut o) {
  __shared__ float s_pk[kBlock * kPackedStride];
  __shared__ float s_ex[kBlock * kMaxExtras];
  const int tile = blockIdx.x;
  const int x = (tile % p.tiles_x) * kTileSize + int(threadIdx.x) % kTileSize;
  const int y = (tile / p.tiles_x) * kTileSize + int(threadIdx.x) / kTileSize;
  const bool inside = x < p.width && y < p.height;
  const std::uint32_t begin = p.ranges[2 * tile], end = p.ranges[2 * tile + 1];
  const int K = p.n_extras;
  const float px = float(x) + 0.5f, py = float(y) + 0.5f;
  float acc[kMaxChannels];
  for (int c = 0; c < kMaxChannels; ++c) acc[c] = 0.f;
  float T = 1.f, med_depth = 0.f;
  std::uint32_t last = begin, median = kNoContributor;
  bool done = !inside;
  for (std::uint32_t b = begin; b < end; b += kBlock) {
    if (__syncthreads_count(done) == kBlock) break;
    const std::uint32_t k_load = b + threadIdx.x;
    stage_batch(p, k_load, k_load < end, s_pk, s_ex);
    __syncthreads();
    const int n = int(min(std::uint32_t(kBlock), end - b));
    for (int j = 0; j < n && !done; ++j) {
      const float* q = &s_pk[j * kPackedStride];
      const Vec2<float> mean(q[kPkMean], q[kPkMean + 1]);
      const Vec3<float> conic(q[kPkConic], q[kPkConic + 1], q[kPkConic + 2]);
      const PixelHit<float> h = eval_hit(mean, conic, q[kPkOpacity], px, py);
      if (h.alpha == 0.f) continue;
      const float test_T = T * (1.f - h.alpha);
      if (test_T < BlendConst<float>::T_min) {
        done = true;
        break;
      }
      const float w = h.alpha * T;
      const float z = plane_depth(q[kPkDepth], Vec2<float>(q[kPkPlane], q[kPkPlane + 1]), h.dx, h.dy);
      acc[0] += w * q[kPkColor];
      acc[1] += w * q[kPkColor + 1];
      acc[2] += w * q[kPkColor + 2];
      acc[kChDepth] += w * z;
      acc[kChNormal] += w * q[kPkNormal];
      acc[kChNormal + 1] += w * q[kPkNormal + 1];
      acc[kChNormal + 2] += w * q[kPkNormal + 2];
      for (int e = 0; e < K; ++e) acc[kChExtras + e] += w * s_ex[j * kMaxExtras + e];
      if (T > 0.5f) {
        median = b + std::uint32_t(j);
        med_depth = z;
      }
      T = test_T;
      last = b + std::uint32_t(j) + 1;
    }
    __syncthreads();
  }
  if (!inside) return;
  const std::size_t P = std::size_t(p.width) * p.height, q = std::size_t(y) * p.width + x;
  for (int c = 0; c < 3; ++c) o.color[c * P + q] = acc[c] + T * p.bg[c];
  o.alpha[q] = 1.f - T;
  o.depth[q] = acc[kChDepth];
  o.median_depth[q] = med_depth;
  for (int c = 0; c < 3; ++c) o.normal[c * P + q] = acc[kChNormal + c];
  for (int e = 0; e < K; ++e) o.extras[e * P + q] = acc[kChExtras + e];
  o.final_T[q] = T;
  o.n_contrib[q] = last;
  o.median_index[q] = median;
}

struct BackwardIn {
  const float *final_T;
  const std::uint32_t *n_contrib, *median_index;
  GBufferGradT<float> go;
  float* partials;  // [instances][stride], zeroed
};

__device__ float warp_sum(float v) {
  for (int off = 16; off > 0; off /= 2) v += __shfl_down_sync(0xffffffffu, v, off);
  return v;
}

constexpr int kWarps = kBlock / 32;
constexpr int kMaxGradStride = kGExtras + kMaxExtras;
constexpr int kGroup = 8;  // instances whose warp sums wait in shared memory (8 KB) before being added

// Slots of the instances j0 .. j0 + count - 1 (batch positions) = their warps' sums added in warp order, so
// the result does not depend on which warp finished first (atomics on the slots did). Each instance
// belongs to one tile, hence one block: a plain store.
__device__ void add_warp_sums(const float* s_warp, const std::uint32_t* s_slot, int j0, int count, int stride,
                              float* partials) {
  for (int e = int(threadIdx.x); e < count * stride; e += kBlock) {
    const int jj = e / stride, c = e % stride;
    float sum = 0.f;
    for (int w = 0; w < kWarps; ++w) sum += s_warp[(jj * kWarps + w) * kMaxGradStride + c];
    if (sum != 0.f) partials[std::size_t(s_slot[j0 + jj]) * stride + c] = sum;
  }
}

// One thread per pixel walks its contributors back to front (3DGS): see raster_backward_cpu.cpp for the
// single-scalar form of the "what lies behind" term. Each warp sums its pixels' gradient for a Gaussian;
// the block adds the warps' sums into the instance's slot in a fixed order.
__global__ void __launch_bounds__(kBlock) blend_backward_kernel(BlendParams p, BackwardIn in) {
  __shared__ float s_pk[kBlock * kPackedStride];
  __shared__ float s_ex[kBlock * kMaxExtras];
  __shared__ std::uint32_t s_slot[kBlock];
  __shared__ float s_warp[kGroup * kWarps * kMaxGradStride];
  const int tile = blockIdx.x;
  const int x = (tile % p.tiles_x) * kTileSize + int(threadIdx.x) % kTileSize;
  const int y = (tile / p.tiles_x) * kTileSize + int(threadIdx.x) / kTileSize;
  const bool inside = x < p.width && y < p.height;
  const std::uint32_t begin = p.ranges[2 * tile];
  const int K = p.n_extras, stride = grad_slot_stride(K);
  const float px = float(x) + 0.5f, py = float(y) + 0.5f;
  const std::size_t P = std::size_t(p.width) * p.height, q = std::size_t(y) * p.width + x;
  float dl[kMaxChannels];
  for (int c = 0; c < kMaxChannels; ++c) dl[c] = 0.f;
  float T = 1.f, T_final = 1.f, dalpha_tf = 0.f, dmedian = 0.f, behind = 0.f;
  std::uint32_t n_contrib = begin, median = kNoContributor;
  if (inside) {
    float dA = in.go.alpha ? in.go.alpha[q] : 0.f;
    if (in.go.color)
      for (int c = 0; c < 3; ++c) {
        dl[c] = in.go.color[c * P + q];
        dA -= p.bg[c] * dl[c];
      }
    if (in.go.depth) dl[kChDepth] = in.go.depth[q];
    if (in.go.normal)
      for (int c = 0; c < 3; ++c) dl[kChNormal + c] = in.go.normal[c * P + q];
    if (in.go.extras)
      for (int e = 0; e < K; ++e) dl[kChExtras + e] = in.go.extras[e * P + q];
    if (in.go.median_depth) dmedian = in.go.median_depth[q];
    T = T_final = in.final_T[q];
    dalpha_tf = dA * T_final;
    n_contrib = in.n_contrib[q];
    median = in.median_index[q];
  }
  // The block starts at the last contributor of any of its pixels.
  __shared__ std::uint32_t s_kend;
  if (threadIdx.x == 0) s_kend = begin;
  __syncthreads();
  atomicMax(&s_kend, n_contrib);
  __syncthreads();
  const std::uint32_t block_end = s_kend;
  for (std::uint32_t b_end = block_end; b_end > begin;) {
    const std::uint32_t b_begin = b_end - min(std::uint32_t(kBlock), b_end - begin);
    const int n = int(b_end - b_begin);
    // Batch [b_begin, b_end): thread t stages instance b_end - 1 - t (back to front order in shared memory).
    __syncthreads();
    if (int(threadIdx.x) < n) {
      const std::uint32_t k = b_end - 1 - threadIdx.x;
      stage_batch(p, k, true, s_pk, s_ex);
      s_slot[threadIdx.x] = p.sorted_slot[k];
    }
    __syncthreads();
    for (int j = 0; j < n; ++j) {
      const std::uint32_t k = b_end - 1 - std::uint32_t(j);
      const float* qk = &s_pk[j * kPackedStride];
      float gs[kGExtras + kMaxExtras];
      for (int c = 0; c < stride; ++c) gs[c] = 0.f;
      bool hit = false;
      if (k < n_contrib) {
        const Vec2<float> mean(qk[kPkMean], qk[kPkMean + 1]);
        const Vec3<float> conic(qk[kPkConic], qk[kPkConic + 1], qk[kPkConic + 2]);
        const float op = qk[kPkOpacity];
        const PixelHit<float> h = eval_hit(mean, conic, op, px, py);
        if (h.alpha != 0.f) {
          hit = true;
          const float one_minus = 1.f - h.alpha;
          const float inv = 1.f / one_minus;
          T = T * inv;
          const float w = h.alpha * T;
          const Vec2<float> plane(qk[kPkPlane], qk[kPkPlane + 1]);
          const float z = plane_depth(qk[kPkDepth], plane, h.dx, h.dy);
          float V = z * dl[kChDepth];
          for (int c = 0; c < 3; ++c) {
            V += qk[kPkColor + c] * dl[c] + qk[kPkNormal + c] * dl[kChNormal + c];
            gs[kGColor + c] = w * dl[c];
            gs[kGNormal + c] = w * dl[kChNormal + c];
          }
          for (int e = 0; e < K; ++e) {
            V += s_ex[j * kMaxExtras + e] * dl[kChExtras + e];
            gs[kGExtras + e] = w * dl[kChExtras + e];
          }
          const float dalpha = T * (V - behind) + dalpha_tf * inv;
          behind = h.alpha * V + one_minus * behind;
          plane_depth_vjp(plane, h.dx, h.dy, w * dl[kChDepth] + (k == median ? dmedian : 0.f), gs);
          eval_hit_vjp(conic, op, h, dalpha, gs);
        }
      }
      // Warp sums of this instance into shared memory; every kGroup instances (and at the batch's end) the
      // block adds them warp by warp into the instances' slots.
      const int jj = j % kGroup, warp = int(threadIdx.x) / 32;
      const bool any = __any_sync(0xffffffffu, hit);
      float* const s_w = &s_warp[(jj * kWarps + warp) * kMaxGradStride];
      for (int c = 0; c < stride; ++c) {
        const float v = any ? warp_sum(gs[c]) : 0.f;
        if ((threadIdx.x & 31) == 0) s_w[c] = v;
      }
      if (jj == kGroup - 1 || j == n - 1) {
        __syncthreads();
        add_warp_sums(s_warp, s_slot, j - jj, jj + 1, stride, in.partials);
        __syncthreads();
      }
    }
    b_end = b_begin;
  }
}

BlendParams blend_params(const GaussiansT<float>& g, const RasterStateT<float>& st) {
  BlendParams p;
  p.ranges = st.tile_ranges.data();
  p.sorted_gauss = st.sorted_gauss.data();
  p.sorted_slot = st.sorted_slot.data();
  p.packed = st.packed.data();
  p.extras = g.extras;
  p.n_extras = g.n_extras;
  p.width = st.camera.width;
  p.height = st.camera.height;
  p.tiles_x = st.tiles_x;
  p.bg[0] = st.settings.background.x, p.bg[1] = st.settings.background.y, p.bg[2] = st.settings.background.z;
  return p;
}

}  // namespace

void forward_cuda(const GaussiansT<float>& g, const Camera& cam, const RasterSettings& settings, GBufferT<float>& out,
                  RasterStateT<float>& st) {
  validate_inputs(g, cam);
  const Device dev = Device::CUDA;
  StageTimer timer(settings.profile, dev);
  Buffer<std::uint32_t> counts;
  preprocess(g, cam, settings, dev, st, counts);
  st.times.preprocess = timer.lap();
  bin_tiles(st, counts);
  st.times.binning = timer.lap();
  const std::size_t P = std::size_t(cam.width) * std::size_t(cam.height);
  out.width = cam.width;
  out.height = cam.height;
  out.n_extras = g.n_extras;
  out.color = Buffer<float>(3 * P, dev);
  out.alpha = Buffer<float>(P, dev);
  out.depth = Buffer<float>(P, dev);
  out.median_depth = Buffer<float>(P, dev);
  out.normal = Buffer<float>(3 * P, dev);
  out.extras = Buffer<float>(std::size_t(g.n_extras) * P, dev);
  st.final_T = Buffer<float>(P, dev);
  st.n_contrib = Buffer<std::uint32_t>(P, dev);
  st.median_index = Buffer<std::uint32_t>(P, dev);
  const ForwardOut o{out.color.data(),  out.alpha.data(),     out.depth.data(),
                     out.median_depth.data(), out.normal.data(), out.extras.data(),
                     st.final_T.data(), st.n_contrib.data(), st.median_index.data()};
  const int n_tiles = st.tiles_x * st.tiles_y;
  {
    kernel_profile::Scope scope(Device::CUDA);
    blend_forward_kernel<<<n_tiles, kBlock>>>(blend_params(g, st), o);
    GORIS_CUDA_CHECK(cudaGetLastError());
  }
  st.times.blend = timer.lap();
}

void backward_cuda(const GaussiansT<float>& g, const RasterStateT<float>& st, const GBufferGradT<float>& grad_out,
                   const GaussianGradsT<float>& out) {
  if (st.device != Device::CUDA) throw Error("rasterizer", "backward_cuda was given a state that lives on the CPU");
  if (g.count != st.count || g.n_extras != st.n_extras || g.sh_degree != st.sh_degree)
    throw Error("rasterizer", "backward pass got a different Gaussian view than its forward pass");
  StageTimer timer(st.settings.profile, Device::CUDA);
  const int stride = grad_slot_stride(st.n_extras);
  Buffer<float> partials(st.n_instances * std::size_t(stride), Device::CUDA);
  partials.fill_zero();
  const BackwardIn in{st.final_T.data(), st.n_contrib.data(), st.median_index.data(), grad_out, partials.data()};
  const int n_tiles = st.tiles_x * st.tiles_y;
  {
    kernel_profile::Scope scope(Device::CUDA);
    blend_backward_kernel<<<n_tiles, kBlock>>>(blend_params(g, st), in);
    GORIS_CUDA_CHECK(cudaGetLastError());
  }
  st.times.backward_blend = timer.lap();
  backward_gaussians(g, st, partials, out);
  st.times.backward_gaussians = timer.lap();
}

}  // namespace goris::raster
