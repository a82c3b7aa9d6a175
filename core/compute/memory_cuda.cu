#include <cstddef>

#include "core/compute/cuda_check.h"

namespace goris {

// Null when the device is out of memory (the caller may free cached blocks and retry); throws otherwise.
void* cuda_alloc(std::size_t bytes) {
  void* p = nullptr;
  const cudaError_t e = cudaMalloc(&p, bytes);
  if (e == cudaErrorMemoryAllocation) {
    (void)cudaGetLastError();  // clear the sticky error state of this call
    return nullptr;
  }
  GORIS_CUDA_CHECK(e);
  return p;
}

void cuda_free(void* p) { cudaFree(p); }  // never throws: called from destructors

void cuda_copy(void* dst, bool dst_cuda, const void* src, bool src_cuda, std::size_t bytes) {
  cudaMemcpyKind kind = dst_cuda ? (src_cuda ? cudaMemcpyDeviceToDevice : cudaMemcpyHostToDevice)
                                 : cudaMemcpyDeviceToHost;
  GORIS_CUDA_CHECK(cudaMemcpy(dst, src, bytes, kind));
}

void cuda_memset_zero(void* p, std::size_t bytes) { GORIS_CUDA_CHECK(cudaMemset(p, 0, bytes)); }

void cuda_sync() { GORIS_CUDA_CHECK(cudaDeviceSynchronize()); }

}  // namespace goris
