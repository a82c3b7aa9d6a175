// CUDA backend of the tracer: the LBVH of trace_build.h built on the GPU, one thread per ray running the
// shared per-ray code (trace_ray.h) with a kCudaHitsPerRound-entry hit list in local memory, and the
// backward pass summing per-Gaussian records with atomics before turning them into parameter gradients.
#include "render/trace/trace_cuda.h"

#include "core/compute/cuda_check.h"
#include "core/compute/parallel_for.h"
#include "render/trace/lbvh.h"
#include "render/trace/trace_build.h"

namespace goris::trace {

namespace {

struct AtomicAcc {
  float* rec;
  GORIS_HD void add(std::size_t i, float v) const {
#if defined(__CUDA_ARCH__)
    if (v != 0.0f) atomicAdd(rec + i, v);
#else
    rec[i] += v;  // never used on the host; keeps the host pass of nvcc well-formed
#endif
  }
};

GORIS_HDI Vec3<float> ray3(const float* p, std::size_t i) { return Vec3<float>(p[3 * i], p[3 * i + 1], p[3 * i + 2]); }

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
    trace_ray(s, ray3(r.origins, i), ray3(r.directions, i), r.t_min, list, collect, res);
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
                   const TraceRayGrads& ray_grads, float* grad_emit) {
  const std::size_t stride = std::size_t(record_stride(sc.sh_degree, sc.n_extras));
  Buffer<float> records(std::size_t(sc.count) * stride, Device::CUDA);
  records.fill_zero();
  const TraceScene<float> s = sc;
  const LbvhView b = bvh;
  const TraceRays r = rays;
  const TraceOutputGrads up_g = grad_out;
  const TraceRayGrads rg = ray_grads;
  const AtomicAcc acc{records.data()};
  parallel_for(Device::CUDA, rays.count, [=] __device__(std::size_t i) {
    constexpr int K = kCudaHitsPerRound;
    float t[K], alpha[K], trans[K], phi[K];
    std::uint32_t id[K];
    HitList<float> list{t, alpha, id, trans, phi, K, 0};
    LbvhCollector collect{b, s.prims};
    AtomicAcc a = acc;
    RayUpstream<float> up;
    Vec3<float> dorig(0.0f), ddir(0.0f);
    if (load_upstream(up_g.color, up_g.depth, up_g.alpha, up_g.extras, s.n_extras, i, up))
      trace_ray_backward(s, ray3(r.origins, i), ray3(r.directions, i), r.t_min, up, list, collect, a, dorig, ddir);
    for (int c = 0; c < 3; ++c) {
      if (rg.origins) rg.origins[3 * i + c] = dorig[c];
      if (rg.directions) rg.directions[3 * i + c] = ddir[c];
    }
  });
  const float* rec = records.data();
  const GaussiansT<float> gv = g;
  const ParamGradOut<float> out{grads.positions, grads.log_scales, grads.rotations, grads.opacity_logits,
                                grads.sh,        grads.extras,     grad_emit};
  const int deg = sc.sh_degree, n_extras = sc.n_extras;
  parallel_for(Device::CUDA, std::size_t(sc.count), [=] __device__(std::size_t i) {
    const float* ri = rec + i * stride;
    bool any = false;
    for (std::size_t k = 0; k < stride; ++k) any = any || ri[k] != 0.0f;
    if (!any) return;  // not hit by any ray with a gradient
    finalize_record(gv.log_scales + 3 * i, gv.rotations + 4 * i, gv.opacity_logits[i],
                    gv.filter3d_var ? gv.filter3d_var[i] : 0.0f, ri, deg, n_extras, i, out);
  });
  sync_and_check();
}

}  // namespace goris::trace
