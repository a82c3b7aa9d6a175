// CUDA backend of the compute primitives (CUB). The CPU twin and the public API are primitives_cpu.cpp.
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>

#include <cstdint>
#include <limits>

#include "core/compute/buffer.h"
#include "core/compute/cuda_check.h"
#include "core/compute/parallel_for.h"

namespace goris {

namespace {
// CUB's two-phase API: ask for the temporary storage size, allocate it, run.
template <class Run>
void with_temp(Run run) {
  std::size_t bytes = 0;
  GORIS_CUDA_CHECK(run(nullptr, bytes));
  Buffer<unsigned char> temp(bytes, Device::CUDA);
  GORIS_CUDA_CHECK(run(temp.data(), bytes));
}

struct MaxOp {
  template <class T>
  __device__ T operator()(const T& a, const T& b) const { return a < b ? b : a; }
};
}  // namespace

void cuda_sort_by_key(std::uint64_t* keys, std::uint32_t* values, std::size_t n, int end_bit) {
  if (n < 2) return;
  Buffer<std::uint64_t> k2(n, Device::CUDA);
  Buffer<std::uint32_t> v2(n, Device::CUDA);
  cub::DoubleBuffer<std::uint64_t> kb(keys, k2.data());
  cub::DoubleBuffer<std::uint32_t> vb(values, v2.data());
  with_temp([&](void* t, std::size_t& b) { return cub::DeviceRadixSort::SortPairs(t, b, kb, vb, int(n), 0, end_bit); });
  if (kb.Current() != keys) {
    GORIS_CUDA_CHECK(cudaMemcpy(keys, kb.Current(), n * sizeof(std::uint64_t), cudaMemcpyDeviceToDevice));
    GORIS_CUDA_CHECK(cudaMemcpy(values, vb.Current(), n * sizeof(std::uint32_t), cudaMemcpyDeviceToDevice));
  }
}

template <class T>
void cuda_scan(const T* in, T* out, std::size_t n, bool inclusive) {
  if (n == 0) return;
  if (inclusive)
    with_temp([&](void* t, std::size_t& b) { return cub::DeviceScan::InclusiveSum(t, b, in, out, int(n)); });
  else
    with_temp([&](void* t, std::size_t& b) { return cub::DeviceScan::ExclusiveSum(t, b, in, out, int(n)); });
}

template <class T>
T cuda_reduce_sum(const T* in, std::size_t n) {
  if (n == 0) return T(0);
  Buffer<T> r(1, Device::CUDA);
  with_temp([&](void* t, std::size_t& b) { return cub::DeviceReduce::Sum(t, b, in, r.data(), int(n)); });
  return r.to_host()[0];
}

template <class T>
T cuda_reduce_max(const T* in, std::size_t n) {
  if (n == 0) return std::numeric_limits<T>::lowest();
  Buffer<T> r(1, Device::CUDA);
  with_temp([&](void* t, std::size_t& b) {
    return cub::DeviceReduce::Reduce(t, b, in, r.data(), int(n), MaxOp{}, std::numeric_limits<T>::lowest());
  });
  return r.to_host()[0];
}

template <class T>
void cuda_add_into(const T* a, T* acc, std::size_t n) {
  parallel_for(Device::CUDA, n, [=] __device__(std::size_t i) { acc[i] += a[i]; });
}
template void cuda_add_into<float>(const float*, float*, std::size_t);
template void cuda_add_into<double>(const double*, double*, std::size_t);

#define GORIS_INSTANTIATE(T)                                                   \
  template void cuda_scan<T>(const T*, T*, std::size_t, bool);                 \
  template T cuda_reduce_sum<T>(const T*, std::size_t);                        \
  template T cuda_reduce_max<T>(const T*, std::size_t);
GORIS_INSTANTIATE(std::int32_t)
GORIS_INSTANTIATE(std::uint32_t)
GORIS_INSTANTIATE(std::uint64_t)
GORIS_INSTANTIATE(float)
GORIS_INSTANTIATE(double)
#undef GORIS_INSTANTIATE

}  // namespace goris
