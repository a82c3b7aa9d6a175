#pragma once
// The tracer's backward pass with its gradient sums in a fixed order, written once on parallel_for: the
// CUDA backend runs it (trace_cuda.cu), the CPU tests run the same code. Each ray writes one record per
// hit (the Gaussian's values from trace_ray_backward) at a slot taken from a shared counter, keyed by
// (Gaussian, ray); add_rows_in_key_order then adds each Gaussian's records in ray order. (Atomic adds into
// per-Gaussian records summed in thread order, so two CUDA runs differed in the last bits and drifted
// apart over a training run.)
//
// Rays go in chunks whose records fit `budget_bytes`. A chunk whose records overflow the slots is traced
// again with fewer rays or exactly enough slots. Chunking does not change the sums: every Gaussian's
// records are still added in ray order, each chunk starting from the total of the chunks before it.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/compute/buffer.h"
#include "core/compute/ordered_sum.h"
#include "core/compute/parallel_for.h"
#include "render/raster/raster_types.h"
#include "render/trace/lbvh.h"
#include "render/trace/trace_ray.h"
#include "render/trace/trace_types.h"

namespace goris::trace {
GORIS_BACKEND_NAMESPACE_BEGIN

// trace_ray_backward's accumulator: the adds of one hit (consecutive, one Gaussian) fill one record.
template <class T>
struct RecordAcc {
  std::uint64_t* keys;
  T* rows;               // [capacity][stride]
  int* cursor;           // records taken so far (may pass capacity: then the chunk is redone)
  std::size_t capacity, stride;
  OrderedKeyLayout layout;
  std::uint64_t ray;     // the ray's order within its chunk
  std::size_t gaussian = ~std::size_t(0), slot = 0;

  GORIS_HD void add(std::size_t index, T v) {
    const std::size_t gi = index / stride;
    if (gi != gaussian) {
      gaussian = gi;
      slot = std::size_t(atomic_add_int(cursor, 1));
      if (slot < capacity) {
        keys[slot] = layout.key(gi, ray);
        for (std::size_t k = 0; k < stride; ++k) rows[slot * stride + k] = T(0);
      }
    }
    if (slot < capacity) rows[slot * stride + index % stride] += v;
  }
};

// Adds dL/dparameters to `grads` (and dL/demit to grad_emit), writes the rays' gradients. `collector` is
// copied per ray (LbvhCollector, BruteForceCollector); K hits per round. Every pointer lives on d.
template <int K, class T, class Collector>
void backward_ordered(Device d, const TraceScene<T>& sc, const Collector& collector, const GaussiansT<T>& g,
                      const TraceRaysT<T>& rays, const TraceOutputGradsT<T>& grad_out,
                      const GaussianGradsT<T>& grads, const TraceRayGradsT<T>& ray_grads, T* grad_emit,
                      std::size_t budget_bytes) {
  const std::size_t stride = std::size_t(record_stride(sc.sh_degree, sc.n_extras));
  const std::size_t count = std::size_t(sc.count);
  Buffer<T> totals(count * stride, d);
  totals.fill_zero();
  // A record costs its row, its key and permutation entry, and their copies in the sort.
  const std::size_t record_bytes = stride * sizeof(T) + 2 * sizeof(std::uint64_t) + 2 * sizeof(std::uint32_t);
  const std::size_t max_records = std::clamp<std::size_t>(budget_bytes / record_bytes, 1, 0x7fffffff);
  constexpr std::size_t kGuessHitsPerRay = 64;  // typical scenes blend 30-45 per ray
  std::size_t chunk = std::max<std::size_t>(1, max_records / kGuessHitsPerRay);
  Buffer<int> cursor(1, d);
  const TraceScene<T> s = sc;
  const Collector coll = collector;
  const TraceRaysT<T> r = rays;
  const TraceOutputGradsT<T> up_g = grad_out;
  const TraceRayGradsT<T> rg = ray_grads;
  for (std::size_t r0 = 0; r0 < rays.count;) {
    const std::size_t len = std::min(chunk, rays.count - r0);
    std::size_t capacity = std::min(max_records, len * kGuessHitsPerRay);
    for (;;) {
      Buffer<std::uint64_t> keys(capacity, d);
      Buffer<T> rows(capacity * stride, d);
      cursor.fill_zero();
      const RecordAcc<T> acc0{keys.data(), rows.data(), cursor.data(), capacity, stride,
                              OrderedKeyLayout(count, len), 0};
      parallel_for(d, len, [=] GORIS_HD(std::size_t j) {
        const std::size_t i = r0 + j;
        T t[K], alpha[K], trans[K], phi[K];
        std::uint32_t id[K];
        HitList<T> list{t, alpha, id, trans, phi, K, 0};
        Collector c = coll;
        RecordAcc<T> acc = acc0;
        acc.ray = j;
        RayUpstream<T> up;
        Vec3<T> dorig(T(0)), ddir(T(0));
        if (load_upstream(up_g.color, up_g.depth, up_g.alpha, up_g.extras, s.n_extras, i, up))
          trace_ray_backward(s, ray_at(r.origins, i), ray_at(r.directions, i), r.t_min, up, list, c, acc, dorig, ddir);
        for (int k = 0; k < 3; ++k) {
          if (rg.origins) rg.origins[3 * i + k] = dorig[k];
          if (rg.directions) rg.directions[3 * i + k] = ddir[k];
        }
      }, 8);
      int taken = 0;
      cursor.download(&taken);
      const std::size_t n = std::size_t(taken);
      if (n <= capacity) {
        keys.resize(n);
        add_rows_in_key_order(acc0.layout, keys, rows.data(), int(stride), totals.data());
        r0 += len;
        break;
      }
      if (n > max_records && len > 1) {  // over the budget: fewer rays per chunk from here on
        chunk = std::max<std::size_t>(1, len / 2);
        break;
      }
      capacity = n;  // the exact count: the second pass fits
    }
  }
  const T* const rec = totals.data();
  const GaussiansT<T> gv = g;
  const ParamGradOut<T> out{grads.positions, grads.log_scales, grads.rotations, grads.opacity_logits,
                            grads.sh,        grads.extras,     grad_emit};
  const int deg = sc.sh_degree, n_extras = sc.n_extras;
  parallel_for(d, count, [=] GORIS_HD(std::size_t i) {
    const T* ri = rec + i * stride;
    bool any = false;
    for (std::size_t k = 0; k < stride; ++k) any = any || ri[k] != T(0);
    if (!any) return;  // not hit by any ray with a gradient
    finalize_record(gv.log_scales + 3 * i, gv.rotations + 4 * i, gv.opacity_logits[i],
                    gv.filter3d_var ? gv.filter3d_var[i] : T(0), ri, deg, n_extras, i, out);
  });
}

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris::trace
