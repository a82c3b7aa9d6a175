#include "core/compute/memory.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#include "core/compute/block_cache.h"
#include "core/util/error.h"

namespace goris {

#ifdef GORIS_WITH_CUDA
void* cuda_alloc(std::size_t bytes);  // memory_cuda.cu (null when out of memory)
void cuda_free(void* p);
void cuda_copy(void* dst, bool dst_cuda, const void* src, bool src_cuda, std::size_t bytes);
void cuda_memset_zero(void* p, std::size_t bytes);
void cuda_sync();
#else
[[noreturn]] static void no_cuda() {
  throw Error("CUDA memory requested, but this build has no CUDA backend (nvcc was not found at configure time)");
}
#endif

namespace {

#ifdef GORIS_WITH_CUDA
// CUDA blocks go through a cache (block_cache.h); GORIS_CUDA_CACHE=0 frees every block at once, for
// memory checkers. Never destroyed: at exit the runtime may be gone before static destructors run.
BlockCache& cuda_cache() {
  static BlockCache* cache = [] {
    const char* env = std::getenv("GORIS_CUDA_CACHE");
    const bool enabled = !(env && std::string(env) == "0");
    auto* c = new BlockCache(cuda_alloc, cuda_free, enabled);
    std::atexit(write_device_memory_report);
    return c;
  }();
  return *cache;
}

std::string mib(std::size_t bytes) { return std::to_string((bytes + (1u << 19)) >> 20) + " MiB"; }
#endif

}  // namespace

DeviceMemoryStats device_memory_stats(Device d) {
#ifdef GORIS_WITH_CUDA
  if (d == Device::CUDA) return cuda_cache().stats();
#else
  (void)d;
#endif
  return {};
}

void write_device_memory_report() {
  const char* path = std::getenv("GORIS_DEVICE_MEMORY_REPORT");
  if (!path || !*path) return;
  const DeviceMemoryStats s = device_memory_stats(Device::CUDA);
  if (FILE* f = std::fopen(path, "w")) {
    std::fprintf(f, "{\"peak_device_memory_bytes\": %zu}\n", s.peak_in_use);
    std::fclose(f);
  }
}

void* device_alloc(Device d, std::size_t bytes) {
  if (bytes == 0) return nullptr;
  if (d == Device::CPU) {
    void* p = std::aligned_alloc(64, (bytes + 63) / 64 * 64);
    if (!p) throw std::bad_alloc();
    return p;
  }
#ifdef GORIS_WITH_CUDA
  void* p = cuda_cache().allocate(bytes);
  if (!p) {
    const DeviceMemoryStats s = cuda_cache().stats();
    throw Error("CUDA out of memory: " + mib(bytes) + " requested with " + mib(s.in_use) +
                " in use by this process (lower the resolution or the Gaussian budget)");
  }
  return p;
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
  cuda_cache().release(p);
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
