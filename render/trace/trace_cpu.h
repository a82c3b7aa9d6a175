#pragma once
// CPU drivers of the tracer, templated on the scalar type and on the hit collector (Embree, the LBVH, or
// brute force): rays run in parallel with oneTBB, each thread with its own hit list. The backward pass sums
// per-Gaussian gradient records in per-slot scratch (no atomics, a fixed sum order), limited in slots by a
// memory cap, then turns them into parameter gradients.
#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "core/compute/kernel_profile.h"
#include "render/raster/raster_types.h"
#include "render/trace/trace_ray.h"
#include "render/trace/trace_types.h"

namespace goris::trace {

// Flush-to-zero and denormals-are-zero for the current thread while alive (Embree asks for it), restoring
// the previous mode after, so other code sharing TBB's workers is unaffected.
class DenormalsOff {
 public:
#if defined(__SSE__) || defined(__x86_64__)
  DenormalsOff() : csr_(_mm_getcsr()) { _mm_setcsr(csr_ | 0x8040u); }
  ~DenormalsOff() { _mm_setcsr(csr_); }

 private:
  unsigned csr_;
#endif
};

// A thread's hit list storage. A round never holds more hits than there are Gaussians, so the capacity is
// min(k, count): "all hits in one round" costs no more memory than the scene.
template <class T>
struct HitScratch {
  std::vector<T> t, alpha, trans, phi;
  std::vector<std::uint32_t> id;
  explicit HitScratch(int cap) : t(cap), alpha(cap), trans(cap), phi(cap), id(cap) {}
  HitList<T> list() {
    return HitList<T>{t.data(), alpha.data(), id.data(), trans.data(), phi.data(), int(t.size()), 0};
  }
};

inline int round_capacity(int k, int count) { return std::max(1, std::min(k, count)); }

// Looks at every Gaussian: the reference the accelerated collectors must agree with.
template <class T>
struct BruteForceCollector {
  const TracePrim<T>* prims;
  int count;
  void operator()(const Vec3<T>& o, const Vec3<T>& d, T t_min, RoundStart<T> start, HitList<T>& l) const {
    for (int i = 0; i < count; ++i) consider_hit(prims[i], std::uint32_t(i), o, d, t_min, start, l);
  }
};

// Prims and boxes ([N][3] lo, hi) of Gaussians on the CPU.
template <class T>
std::vector<TracePrim<T>> make_prims_cpu(const GaussiansT<T>& g, std::type_identity_t<std::vector<T>>* lo = nullptr,
                                         std::type_identity_t<std::vector<T>>* hi = nullptr) {
  std::vector<TracePrim<T>> prims(std::size_t(g.count));
  std::vector<T> l(3 * prims.size()), h(3 * prims.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, prims.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      prims[i] = make_prim(g.positions + 3 * i, g.log_scales + 3 * i, g.rotations + 4 * i, g.opacity_logits[i],
                           g.filter3d_var ? g.filter3d_var[i] : T(0), &l[3 * i], &h[3 * i]);
  });
  if (lo) *lo = std::move(l);
  if (hi) *hi = std::move(h);
  return prims;
}

template <class T, class MakeCollector>
void forward_cpu(const TraceScene<T>& sc, const TraceRaysT<T>& rays, int k, const TraceOutputsT<T>& out,
                 MakeCollector&& make_collector) {
  kernel_profile::Scope scope(Device::CPU);
  tbb::enumerable_thread_specific<HitScratch<T>> scratch(round_capacity(k, sc.count));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.count, 32), [&](const tbb::blocked_range<std::size_t>& r) {
    DenormalsOff ftz;
    HitList<T> list = scratch.local().list();
    auto collect = make_collector();
    RayResult<T> res;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      trace_ray(sc, ray_at(rays.origins, i), ray_at(rays.directions, i), rays.t_min, list, collect, res);
      if (out.color)
        for (int c = 0; c < 3; ++c) out.color[3 * i + c] = res.color[c];
      if (out.depth) out.depth[i] = res.depth;
      if (out.alpha) out.alpha[i] = res.alpha;
      if (out.extras)
        for (int e = 0; e < sc.n_extras; ++e) out.extras[std::size_t(sc.n_extras) * i + e] = res.extras[e];
      if (out.hits) out.hits[i] = res.hits;
    }
  });
}

template <class T>
struct DenseAcc {
  T* rec;
  void add(std::size_t i, T v) { rec[i] += v; }
};

template <class T, class MakeCollector>
void backward_cpu(const TraceScene<T>& sc, const GaussiansT<T>& g, const TraceRaysT<T>& rays, int k,
                  const TraceOutputGradsT<T>& grad_out, const GaussianGradsT<T>& grads,
                  const TraceRayGradsT<T>& ray_grads, T* grad_emit, std::size_t max_scratch_bytes,
                  MakeCollector&& make_collector) {
  kernel_profile::Scope scope(Device::CPU);
  const std::size_t stride = std::size_t(record_stride(sc.sh_degree, sc.n_extras));
  const std::size_t per_slot = std::max<std::size_t>(1, std::size_t(sc.count) * stride * sizeof(T));
  const int slots = int(std::clamp<std::size_t>(max_scratch_bytes / per_slot, 1,
                                                std::size_t(tbb::info::default_concurrency())));
  // Deterministic sums: slot s owns the blocks of 32 rays b = s, s + slots, ... (interleaved, so the slots
  // get similar work) and its own records, summed below in slot order. Which thread runs a slot does not
  // change the result, so a run repeats bit for bit on the same machine (thread-local records did not:
  // the ray-to-thread assignment changes from run to run).
  constexpr std::size_t kBlock = 32;
  const std::size_t blocks = (rays.count + kBlock - 1) / kBlock;
  std::vector<std::vector<T>> records(static_cast<std::size_t>(slots));
  tbb::enumerable_thread_specific<HitScratch<T>> scratch(round_capacity(k, sc.count));
  tbb::task_arena arena(slots);
  arena.execute([&] {
    tbb::parallel_for(0, slots, [&](int slot) {
      DenormalsOff ftz;
      HitList<T> list = scratch.local().list();
      auto collect = make_collector();
      records[std::size_t(slot)].assign(std::size_t(sc.count) * stride, T(0));
      DenseAcc<T> acc{records[std::size_t(slot)].data()};
      RayUpstream<T> up;
      for (std::size_t b = std::size_t(slot); b < blocks; b += std::size_t(slots))
        for (std::size_t i = b * kBlock, end = std::min(rays.count, i + kBlock); i < end; ++i) {
          Vec3<T> dorig(T(0)), ddir(T(0));
          if (load_upstream(grad_out.color, grad_out.depth, grad_out.alpha, grad_out.extras, sc.n_extras, i, up))
            trace_ray_backward(sc, ray_at(rays.origins, i), ray_at(rays.directions, i), rays.t_min, up, list,
                               collect, acc, dorig, ddir);
          for (int c = 0; c < 3; ++c) {
            if (ray_grads.origins) ray_grads.origins[3 * i + c] = dorig[c];
            if (ray_grads.directions) ray_grads.directions[3 * i + c] = ddir[c];
          }
        }
    });
  });
  std::vector<const T*> parts;
  for (const auto& v : records) parts.push_back(v.data());
  const ParamGradOut<T> out{grads.positions, grads.log_scales, grads.rotations, grads.opacity_logits,
                            grads.sh,        grads.extras,     grad_emit};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, std::size_t(sc.count), 256), [&](const auto& r) {
    std::vector<T> rec(stride);
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::fill(rec.begin(), rec.end(), T(0));
      bool any = false;
      for (const T* p : parts)
        for (std::size_t s = 0; s < stride; ++s) {
          rec[s] += p[i * stride + s];
          any = any || p[i * stride + s] != T(0);
        }
      if (!any) continue;  // not hit by any ray with a gradient
      finalize_record(g.log_scales + 3 * i, g.rotations + 4 * i, g.opacity_logits[i],
                      g.filter3d_var ? g.filter3d_var[i] : T(0), rec.data(), sc.sh_degree, sc.n_extras, i, out);
    }
  });
}

}  // namespace goris::trace
