// CPU backend of the compute primitives (oneTBB). The CUDA twin is primitives_cuda.cu.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/kernel_profile.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "core/util/error.h"

namespace goris {

// The CUDA entry points (primitives_cuda.cu).
void cuda_sort_by_key(std::uint64_t* keys, std::uint32_t* values, std::size_t n, int end_bit);
template <class T> void cuda_scan(const T* in, T* out, std::size_t n, bool inclusive);
template <class T> T cuda_reduce_sum(const T* in, std::size_t n);
template <class T> T cuda_reduce_max(const T* in, std::size_t n);
template <class T> void cuda_add_into(const T* a, T* acc, std::size_t n);

namespace {

// Parallel LSD radix sort, 8 bits per pass. Each pass: per-chunk digit histograms (parallel), a global
// prefix over (digit, chunk), then each chunk scatters its elements in order (parallel) - stable.
void cpu_sort_by_key(std::uint64_t* keys, std::uint32_t* values, std::size_t n, int end_bit) {
  if (n < 2) return;
  constexpr int kBits = 8, kDigits = 1 << kBits;
  const std::size_t chunk = std::max<std::size_t>(4096, (n + 63) / 64);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<std::uint64_t> k2(n);
  std::vector<std::uint32_t> v2(n);
  std::vector<std::size_t> hist(chunks * kDigits);
  std::uint64_t *ks = keys, *kd = k2.data();
  std::uint32_t *vs = values, *vd = v2.data();
  for (int shift = 0; shift < end_bit; shift += kBits) {
    std::fill(hist.begin(), hist.end(), 0);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
      std::size_t* h = &hist[c * kDigits];
      for (std::size_t i = c * chunk, e = std::min(n, i + chunk); i < e; ++i) ++h[(ks[i] >> shift) & (kDigits - 1)];
    });
    std::size_t sum = 0;
    for (int d = 0; d < kDigits; ++d)
      for (std::size_t c = 0; c < chunks; ++c) {
        std::size_t t = hist[c * kDigits + d];
        hist[c * kDigits + d] = sum;
        sum += t;
      }
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
      std::size_t* h = &hist[c * kDigits];
      for (std::size_t i = c * chunk, e = std::min(n, i + chunk); i < e; ++i) {
        std::size_t dst = h[(ks[i] >> shift) & (kDigits - 1)]++;
        kd[dst] = ks[i];
        vd[dst] = vs[i];
      }
    });
    std::swap(ks, kd);
    std::swap(vs, vd);
  }
  if (ks != keys) {
    std::copy(ks, ks + n, keys);
    std::copy(vs, vs + n, values);
  }
}

template <class T>
struct Sum {
  // Floating sums accumulate in double on the CPU: the reference the CUDA path is compared against.
  using Acc = std::conditional_t<std::is_floating_point_v<T>, double, T>;
};

template <class T>
void cpu_scan(const T* in, T* out, std::size_t n, bool inclusive) {
  std::vector<T> copy;
  if (in == out) {  // keep the parallel scan free of aliasing
    copy.assign(in, in + n);
    in = copy.data();
  }
  using Acc = typename Sum<T>::Acc;
  tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n, 1024), Acc(0),
      [&](const tbb::blocked_range<std::size_t>& r, Acc acc, bool final) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if (final && !inclusive) out[i] = T(acc);
          acc += Acc(in[i]);
          if (final && inclusive) out[i] = T(acc);
        }
        return acc;
      },
      [](Acc a, Acc b) { return a + b; });
}

}  // namespace

void sort_by_key(Buffer<std::uint64_t>& keys, Buffer<std::uint32_t>& values, int end_bit) {
  if (keys.size() != values.size())
    throw Error("sort_by_key: " + std::to_string(keys.size()) + " keys but " + std::to_string(values.size()) + " values");
  if (keys.device() != values.device()) throw Error("sort_by_key: keys and values live on different devices");
  end_bit = std::clamp(end_bit, 1, 64);
  kernel_profile::Scope scope(keys.device());
  if (keys.device() == Device::CUDA)
    return GORIS_CUDA_CALL("sort_by_key", cuda_sort_by_key(keys.data(), values.data(), keys.size(), end_bit));
  cpu_sort_by_key(keys.data(), values.data(), keys.size(), end_bit);
}

template <class T>
static void scan(const Buffer<T>& in, Buffer<T>& out, bool inclusive) {
  if (out.size() != in.size() || out.device() != in.device())
    throw Error("scan: output must have the input's size and device");
  kernel_profile::Scope scope(in.device());
  if (in.device() == Device::CUDA)
    return GORIS_CUDA_CALL("scan", cuda_scan<T>(in.data(), out.data(), in.size(), inclusive));
  cpu_scan<T>(in.data(), out.data(), in.size(), inclusive);
}

template <class T>
void exclusive_scan(const Buffer<T>& in, Buffer<T>& out) { scan(in, out, false); }
template <class T>
void inclusive_scan(const Buffer<T>& in, Buffer<T>& out) { scan(in, out, true); }

template <class T>
T reduce_sum(const Buffer<T>& in) {
  if (in.device() == Device::CUDA) return GORIS_CUDA_CALL("reduce_sum", cuda_reduce_sum<T>(in.data(), in.size()));
  using Acc = typename Sum<T>::Acc;
  const T* p = in.data();
  return T(tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, in.size(), 4096), Acc(0),
      [p](const tbb::blocked_range<std::size_t>& r, Acc acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) acc += Acc(p[i]);
        return acc;
      },
      [](Acc a, Acc b) { return a + b; }));
}

template <class T>
T reduce_max(const Buffer<T>& in) {
  if (in.device() == Device::CUDA) return GORIS_CUDA_CALL("reduce_max", cuda_reduce_max<T>(in.data(), in.size()));
  const T* p = in.data();
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, in.size(), 4096), std::numeric_limits<T>::lowest(),
      [p](const tbb::blocked_range<std::size_t>& r, T m) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) m = std::max(m, p[i]);
        return m;
      },
      [](T a, T b) { return std::max(a, b); });
}

template <class T>
void add_into(Device d, const T* a, T* acc, std::size_t n) {
  if (d == Device::CUDA) return GORIS_CUDA_CALL("add_into", cuda_add_into<T>(a, acc, n));
  parallel_for(Device::CPU, n, [=](std::size_t i) { acc[i] += a[i]; }, 8192);
}
template void add_into<float>(Device, const float*, float*, std::size_t);
template void add_into<double>(Device, const double*, double*, std::size_t);

#define GORIS_INSTANTIATE(T)                                         \
  template void exclusive_scan<T>(const Buffer<T>&, Buffer<T>&);     \
  template void inclusive_scan<T>(const Buffer<T>&, Buffer<T>&);     \
  template T reduce_sum<T>(const Buffer<T>&);                        \
  template T reduce_max<T>(const Buffer<T>&);
GORIS_INSTANTIATE(std::int32_t)
GORIS_INSTANTIATE(std::uint32_t)
GORIS_INSTANTIATE(std::uint64_t)
GORIS_INSTANTIATE(float)
GORIS_INSTANTIATE(double)
#undef GORIS_INSTANTIATE

}  // namespace goris
