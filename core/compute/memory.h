#pragma once
#include <cstddef>

#include "core/compute/device.h"

namespace goris {

// Raw memory on one device. CPU memory is 64-byte aligned. Copies between any two devices are explicit
// and synchronous. Using Device::CUDA in a build without CUDA throws goris::Error.
void* device_alloc(Device d, std::size_t bytes);
void device_free(Device d, void* p);
void device_copy(void* dst, Device dst_dev, const void* src, Device src_dev, std::size_t bytes);
void device_memset_zero(Device d, void* p, std::size_t bytes);
void device_synchronize(Device d);

}  // namespace goris
