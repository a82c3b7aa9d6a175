#pragma once
// parallel_for(device, n, fn): calls fn(i) for i in [0, n) on the chosen backend.
// fn must be a GORIS_HD callable that captures by value (it is copied to the GPU). The CPU path uses
// oneTBB; the CUDA path launches a kernel and is only available in translation units compiled by nvcc
// (.cu files), which is how one kernel source serves both backends: a .cpp driver and a .cu driver
// include the same GORIS_HD maths. With kernel_profile enabled, each call's time is recorded under its
// call site (the defaulted source_location).
#include <cstddef>
#include <source_location>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/compute/device.h"
#include "core/compute/hd.h"
#include "core/compute/kernel_profile.h"
#include "core/util/error.h"

#if defined(__CUDACC__)
#include "core/compute/cuda_check.h"
#endif

namespace goris {
GORIS_BACKEND_NAMESPACE_BEGIN

#if defined(__CUDACC__)
template <class F>
__global__ void parallel_for_kernel(std::size_t n, F fn) {
  std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n) fn(i);
}
#endif

template <class F>
void parallel_for(Device d, std::size_t n, F fn, std::size_t cpu_grain = 256,
                  const std::source_location& site = std::source_location::current()) {
  if (n == 0) return;
  if (d == Device::CPU) {
    kernel_profile::Scope timed(Device::CPU, site);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, cpu_grain), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
    });
    return;
  }
#if defined(__CUDACC__)
  constexpr unsigned block = 256;
  const bool profile = kernel_profile::enabled();  // kernel time between two events (Scope would add launch latency)
  static thread_local cudaEvent_t start = nullptr, stop = nullptr;
  if (profile) {
    if (!start) {  // one pair per instantiation and thread, kept for the process's life
      GORIS_CUDA_CHECK(cudaEventCreate(&start));
      GORIS_CUDA_CHECK(cudaEventCreate(&stop));
    }
    GORIS_CUDA_CHECK(cudaEventRecord(start));
  }
  parallel_for_kernel<<<unsigned((n + block - 1) / block), block>>>(n, fn);
  GORIS_CUDA_CHECK(cudaGetLastError());
  if (profile) {
    float ms = 0;
    GORIS_CUDA_CHECK(cudaEventRecord(stop));
    GORIS_CUDA_CHECK(cudaEventSynchronize(stop));
    GORIS_CUDA_CHECK(cudaEventElapsedTime(&ms, start, stop));
    kernel_profile::record(site, ms);
  }
#else
  (void)site;
  throw Error("parallel_for on CUDA was called from a host-only translation unit (move the caller into a .cu file)");
#endif
}

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris
