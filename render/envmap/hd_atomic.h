#pragma once
// atomic_add_hd(p, v): *p += v atomically on either backend, for gradient scatters where several threads
// hit the same element (many pixels look up the same cube-map texels). CUDA: atomicAdd (double needs
// sm_60+, which every architecture we compile for has); host: std::atomic_ref, relaxed ordering because
// only the final sums are read, after the parallel loop has joined.
#include <atomic>

#include "core/compute/hd.h"

namespace goris::envmap {

template <class T>
GORIS_HDI void atomic_add_hd(T* p, T v) {
#if defined(__CUDA_ARCH__)
  atomicAdd(p, v);
#else
  std::atomic_ref<T>(*p).fetch_add(v, std::memory_order_relaxed);
#endif
}

}  // namespace goris::envmap
