#pragma once
// The passes of frame_layout.h written once with GORIS_HD and parallel_for: frame_layout.cpp instantiates
// them on the CPU, frame_layout_cuda.cu on CUDA. Each writes only its own pixel's entries.
#include <cmath>
#include <cstddef>

#include "core/compute/hd.h"
#include "core/compute/parallel_for.h"

namespace goris::ui::frame_layout {

template <Device D>
void interleave_on(const float* planar, int first, int count, std::size_t hw, float* out, int stride, int at) {
  parallel_for(D, hw, [=] GORIS_HD(std::size_t p) {
    for (int c = 0; c < count; ++c) out[p * stride + at + c] = planar[std::size_t(first + c) * hw + p];
  });
}

template <Device D>
void fill_on(float* out, std::size_t hw, int stride, int at, float value) {
  parallel_for(D, hw, [=] GORIS_HD(std::size_t p) { out[p * stride + at] = value; });
}

template <Device D>
void unit_normals_on(const float* normal, const float* alpha, std::size_t hw, float min_alpha, float* out, int stride) {
  parallel_for(D, hw, [=] GORIS_HD(std::size_t p) {
    const float x = normal[p], y = normal[hw + p], z = normal[2 * hw + p];
    const float len = sqrtf(x * x + y * y + z * z);
    const bool unit = alpha[p] >= min_alpha && len > 1e-8f;
    out[p * stride + 0] = unit ? x / len : 0.0f;
    out[p * stride + 1] = unit ? y / len : 0.0f;
    out[p * stride + 2] = unit ? z / len : 0.0f;
  });
}

template <Device D>
void clamp_unit_on(const float* in, std::size_t n, float* out) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) { out[i] = fminf(fmaxf(in[i], 0.0f), 1.0f); });
}

// The CUDA instantiations (frame_layout_cuda.cu; a build without CUDA throws at the call, GORIS_CUDA_CALL).
namespace cuda {
void interleave(const float* planar, int first, int count, std::size_t hw, float* out, int stride, int at);
void fill(float* out, std::size_t hw, int stride, int at, float value);
void unit_normals(const float* normal, const float* alpha, std::size_t hw, float min_alpha, float* out, int stride);
void clamp_unit(const float* in, std::size_t n, float* out);
}  // namespace cuda

}  // namespace goris::ui::frame_layout
