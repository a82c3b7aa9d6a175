#pragma once
// Public types of the Gaussian ray tracer, templated on the scalar type like the rasterizer's (float in
// production, double in the gradient tests). Rays and per-ray outputs are row-major arrays [n][...] on the
// tracer's device; null output pointers are not written.
#include <cstddef>
#include <cstdint>

namespace goris {

// The CPU acceleration structure: Embree (production) or the LBVH the CUDA backend uses, run on the CPU
// (for tests and comparisons). CUDA always uses the LBVH.
enum class TraceAccel { Embree, Lbvh };

struct TraceSettings {
  // Hits gathered per round on the CPU (the k nearest after the previous round). Rays with more hits are
  // traced in several rounds; a full list shrinks the ray so that farther boxes are culled. 128 is as fast
  // as collecting every hit on the fixture scene (max 133 hits per ray) while keeping per-ray work bounded
  // behind opaque surfaces. The CUDA backend uses a fixed round size (trace_cuda.h).
  int hits_per_round = 128;
  TraceAccel cpu_accel = TraceAccel::Embree;
  // Refit the BVH instead of rebuilding it when build() sees the same number of Gaussians as before.
  bool refit = true;
  // Memory cap of the backward pass's gradient scratch: on the CPU the per-thread records (threads are
  // limited to fit it), on CUDA the per-hit records of one chunk of rays (trace_backward_ordered.h).
  std::size_t max_grad_scratch_bytes = std::size_t(512) << 20;
};

template <class T>
struct TraceRaysT {
  const T* origins = nullptr;     // [n][3]
  const T* directions = nullptr;  // [n][3] any non-zero length; t* and depth are in units of |d|
  std::size_t count = 0;
  T t_min = T(0);                 // hits need t* > t_min (>= 0)
};

// Per ray: colour = sum w emit c (c = SH in the ray direction + 0.5, clamped at 0), depth = sum w t*
// (not normalised), alpha = 1 - T, extras = sum w e, hits = number of Gaussians blended.
template <class T>
struct TraceOutputsT {
  T* color = nullptr;   // [n][3]
  T* depth = nullptr;   // [n]
  T* alpha = nullptr;   // [n]
  T* extras = nullptr;  // [n][n_extras]
  std::int32_t* hits = nullptr;  // [n]
};

// dL/d(outputs), same layouts; null channels have zero gradient.
template <class T>
struct TraceOutputGradsT {
  const T* color = nullptr;
  const T* depth = nullptr;
  const T* alpha = nullptr;
  const T* extras = nullptr;
};

// dL/d(ray origin) and dL/d(ray direction) per ray, [n][3]; written (not accumulated); null: not written.
template <class T>
struct TraceRayGradsT {
  T* origins = nullptr;
  T* directions = nullptr;
};

using TraceRays = TraceRaysT<float>;
using TraceOutputs = TraceOutputsT<float>;
using TraceOutputGrads = TraceOutputGradsT<float>;
using TraceRayGrads = TraceRayGradsT<float>;

}  // namespace goris
