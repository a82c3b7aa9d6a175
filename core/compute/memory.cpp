#include "core/compute/memory.h"

#include <cstdlib>
#include <cstring>
#include <new>

#include "core/util/error.h"

namespace goris {

#ifdef GORIS_WITH_CUDA
void* cuda_alloc(std::size_t bytes);  // memory_cuda.cu
void cuda_free(void* p);
void cuda_copy(void* dst, bool dst_cuda, const void* src, bool src_cuda, std::size_t bytes);
void cuda_memset_zero(void* p, std::size_t bytes);
void cuda_sync();
#else
[[noreturn]] static void no_cuda() {
  throw Error("CUDA memory requested, but this build has no CUDA backend (nvcc was not found at configure time)");
}
#endif

void* device_alloc(Device d, std::size_t bytes) {
  if (bytes == 0) return nullptr;
  if (d == Device::CPU) {
    void* p = std::aligned_alloc(64, (bytes + 63) / 64 * 64);
    if (!p) throw std::bad_alloc();
    return p;
  }
#ifdef GORIS_WITH_CUDA
  return cuda_alloc(bytes);
#else
  no_cuda();
#endif
}

void device_free(Device d, void* p) {
  if (!p) return;
  if (d == Device::CPU) {
    std::free(p);
    return;
  }
#ifdef GORIS_WITH_CUDA
  cuda_free(p);
#else
  no_cuda();
#endif
}

void device_copy(void* dst, Device dst_dev, const void* src, Device src_dev, std::size_t bytes) {
  if (bytes == 0) return;
  if (dst_dev == Device::CPU && src_dev == Device::CPU) {
    std::memcpy(dst, src, bytes);
    return;
  }
#ifdef GORIS_WITH_CUDA
  cuda_copy(dst, dst_dev == Device::CUDA, src, src_dev == Device::CUDA, bytes);
#else
  no_cuda();
#endif
}

void device_memset_zero(Device d, void* p, std::size_t bytes) {
  if (bytes == 0) return;
  if (d == Device::CPU) {
    std::memset(p, 0, bytes);
    return;
  }
#ifdef GORIS_WITH_CUDA
  cuda_memset_zero(p, bytes);
#else
  no_cuda();
#endif
}

void device_synchronize(Device d) {
  if (d == Device::CPU) return;
#ifdef GORIS_WITH_CUDA
  cuda_sync();
#else
  no_cuda();
#endif
}

}  // namespace goris
