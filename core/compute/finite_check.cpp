#include "core/compute/finite_check.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/compute/cuda_dispatch.h"
#include "core/util/error.h"

namespace goris {

size_t first_non_finite(const float* data, size_t n, Device d) {
  if (d == Device::CUDA) return GORIS_CUDA_CALL("first_non_finite", detail::first_non_finite_cuda(data, n));
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 16384), n,
      [&](const tbb::blocked_range<size_t>& r, size_t best) {
        for (size_t i = r.begin(); i != r.end() && i < best; ++i)
          if (!std::isfinite(data[i])) return i;
        return best;
      },
      [](size_t a, size_t b) { return std::min(a, b); });
}

}  // namespace goris
