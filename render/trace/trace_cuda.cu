// CUDA backend of the tracer: the LBVH of trace_build.h built on the GPU, one thread per ray running the
// shared per-ray code (trace_ray.h) with a kCudaHitsPerRound-entry hit list in local memory, and the
// backward pass summing per-hit records in a fixed order (trace_backward_ordered.h).
#include "render/trace/trace_cuda.h"

#include "core/compute/cuda_check.h"
#include "core/compute/parallel_for.h"
#include "render/trace/lbvh.h"
#include "render/trace/trace_backward_ordered.h"
#include "render/trace/trace_build.h"

namespace goris::trace {

namespace {

void sync_and_check() { GORIS_CUDA_CHECK(cudaDeviceSynchronize()); }

}  // namespace

void build_cuda(const GaussiansT<float>& g, PrimData& prims, LbvhData& bvh) {
  build_prims<Device::CUDA>(g, prims);
  build_lbvh<Device::CUDA>(prims, bvh);
  sync_and_check();
}

void forward_cuda(const TraceScene<float>& sc, const LbvhView& bvh, const TraceRays& rays, const TraceOutputs& out) {
  const TraceScene<float> s = sc;
  const LbvhView b = bvh;
  const TraceRays r = rays;
  const TraceOutputs o = out;
  parallel_for(Device::CUDA, rays.count, [=] __device__(std::size_t i) {
    constexpr int K = kCudaHitsPerRound;
    float t[K], alpha[K];
    std::uint32_t id[K];
    HitList<float> list{t, alpha, id, nullptr, nullptr, K, 0};
    LbvhCollector collect{b, s.prims};
    RayResult<float> res;
    trace_ray(s, ray_at(r.origins, i), ray_at(r.directions, i), r.t_min, list, collect, res);
    if (o.color)
      for (int c = 0; c < 3; ++c) o.color[3 * i + c] = res.color[c];
    if (o.depth) o.depth[i] = res.depth;
    if (o.alpha) o.alpha[i] = res.alpha;
    if (o.extras)
      for (int e = 0; e < s.n_extras; ++e) o.extras[std::size_t(s.n_extras) * i + e] = res.extras[e];
    if (o.hits) o.hits[i] = res.hits;
  });
  sync_and_check();
}

void backward_cuda(const TraceScene<float>& sc, const LbvhView& bvh, const GaussiansT<float>& g,
                   const TraceRays& rays, const TraceOutputGrads& grad_out, const GaussianGradsT<float>& grads,
                   const TraceRayGrads& ray_grads, float* grad_emit, std::size_t budget_bytes) {
  backward_ordered<kCudaHitsPerRound>(Device::CUDA, sc, LbvhCollector{bvh, sc.prims}, g, rays, grad_out, grads,
                                      ray_grads, grad_emit, budget_bytes);
  sync_and_check();
}

}  // namespace goris::trace
