#pragma once
#include <cstddef>
#include <vector>

#include "core/compute/device.h"

namespace goris {

// Raw memory on one device. CPU memory is 64-byte aligned. Copies between any two devices are explicit
// and synchronous. Using Device::CUDA in a build without CUDA throws goris::Error.
void* device_alloc(Device d, std::size_t bytes);
void device_free(Device d, void* p);
void device_copy(void* dst, Device dst_dev, const void* src, Device src_dev, std::size_t bytes);
void device_memset_zero(Device d, void* p, std::size_t bytes);
void device_synchronize(Device d);

// A host copy of n elements at p on device d (for part of a Buffer; a whole one has Buffer::to_host()).
template <class T>
std::vector<T> download(const T* p, std::size_t n, Device d) {
  std::vector<T> h(n);
  device_copy(h.data(), Device::CPU, p, d, n * sizeof(T));
  return h;
}

}  // namespace goris
