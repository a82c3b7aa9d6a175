// CUDA twin of first_non_finite (finite_check.h).
#include "core/compute/buffer.h"
#include "core/compute/finite_check.h"
#include "core/compute/parallel_for.h"

namespace goris::detail {

size_t first_non_finite_cuda(const float* data, size_t n) {
  const unsigned long long none = n;
  Buffer<unsigned long long> first(1, Device::CUDA);
  first.upload(&none, 1);
  unsigned long long* f = first.data();
  parallel_for(Device::CUDA, n, [=] __device__(size_t i) {
    if (!isfinite(data[i])) atomicMin(f, (unsigned long long)i);
  });
  unsigned long long out = none;
  first.download(&out);
  return size_t(out);
}

}  // namespace goris::detail
