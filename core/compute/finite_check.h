#pragma once
// Detecting NaN / Inf in device buffers (the trainer stops on the first one, naming what went wrong).
#include <cstddef>

#include "core/compute/device.h"

namespace goris {

// Index of the first NaN or +-Inf among data[0..n) (pointer on device d), or n when all are finite.
size_t first_non_finite(const float* data, size_t n, Device d);

namespace detail {
size_t first_non_finite_cuda(const float* data, size_t n);  // finite_check_cuda.cu, through GORIS_CUDA_CALL
}  // namespace detail

}  // namespace goris
