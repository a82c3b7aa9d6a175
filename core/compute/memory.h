#pragma once
#include <cstddef>
#include <vector>

#include "core/compute/block_cache.h"
#include "core/compute/device.h"

namespace goris {

// Raw memory on one device. CPU memory is 64-byte aligned; CUDA memory comes from a caching allocator
// (block_cache.h). Copies between any two devices are explicit and synchronous. Using Device::CUDA in a
// build without CUDA throws goris::Error; running out of CUDA memory throws goris::Error with the sizes.
void* device_alloc(Device d, std::size_t bytes);
void device_free(Device d, void* p);
void device_copy(void* dst, Device dst_dev, const void* src, Device src_dev, std::size_t bytes);
void device_memset_zero(Device d, void* p, std::size_t bytes);
void device_synchronize(Device d);

// CUDA: the caching allocator's statistics (block_cache.h); the CPU is not tracked (all zero).
DeviceMemoryStats device_memory_stats(Device d);
// When GORIS_DEVICE_MEMORY_REPORT names a file, writes {"peak_device_memory_bytes": N} there (CUDA's
// peak in use; 0 when the process used no GPU memory). Runs at exit once CUDA memory was allocated, so a
// parent process (goris bench pipeline) learns each step's peak.
void write_device_memory_report();

// A host copy of n elements at p on device d (for part of a Buffer; a whole one has Buffer::to_host()).
template <class T>
std::vector<T> download(const T* p, std::size_t n, Device d) {
  std::vector<T> h(n);
  device_copy(h.data(), Device::CPU, p, d, n * sizeof(T));
  return h;
}

}  // namespace goris
