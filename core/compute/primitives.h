#pragma once
// Data-parallel building blocks on Buffers, each on the buffer's own device:
//   CPU  - oneTBB (parallel LSD radix sort, parallel_scan, parallel_reduce)
//   CUDA - CUB (DeviceRadixSort, DeviceScan, DeviceReduce)
// Both sorts are stable LSD radix sorts, so CPU and CUDA give identical orders for equal keys.
// All buffers passed to one call must live on the same device.
#include <cstdint>

#include "core/compute/buffer.h"

namespace goris {

// Sorts keys ascending over bits [0, end_bit) and permutes values the same way (stable).
// Passing end_bit < 64 when the high bits are known to be zero saves passes.
void sort_by_key(Buffer<std::uint64_t>& keys, Buffer<std::uint32_t>& values, int end_bit = 64);

// out[i] = in[0] + ... + in[i-1] (exclusive) or ... + in[i] (inclusive). out may alias in.
// Supported T: std::int32_t, std::uint32_t, std::uint64_t, float, double.
template <class T>
void exclusive_scan(const Buffer<T>& in, Buffer<T>& out);
template <class T>
void inclusive_scan(const Buffer<T>& in, Buffer<T>& out);

// acc[i] += a[i] for i < n, pointers on device d. Supported T: float, double.
template <class T>
void add_into(Device d, const T* a, T* acc, std::size_t n);

// Sum and maximum of all elements (0 and lowest() for an empty buffer). Same supported T as the scans.
template <class T>
T reduce_sum(const Buffer<T>& in);
template <class T>
T reduce_max(const Buffer<T>& in);

}  // namespace goris
