#include <cstddef>

#include "core/compute/cuda_check.h"

namespace goris {

void* cuda_alloc(std::size_t bytes) {
  void* p = nullptr;
  GORIS_CUDA_CHECK(cudaMalloc(&p, bytes));
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
