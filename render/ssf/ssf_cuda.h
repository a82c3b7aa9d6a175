#pragma once
// CUDA entry points of the glossy filter and the roughness net (ssf_cuda.cu: the same passes as the CPU,
// instantiated for Device::CUDA and float). Without CUDA the call throws goris::Error (GORIS_CUDA_CALL).
#include <cstddef>

#include "render/ssf/conv_passes.h"
#include "render/ssf/pyramid_passes.h"

namespace goris::ssf::cuda {

void normalise_normals(const float* n_in, float* n_out, std::size_t plane);
void build_levels(const PyramidPtrs<float>& P);
void sample_all(const PyramidPtrs<float>& P, const float* rs, float* out);
void backward_rs(const PyramidPtrs<float>& P, const float* rs, const float* g_out, float* grad_rs);
void backward_x(const PyramidPtrs<float>& P, const PyramidPtrs<float>& scratch, const float* rs, const float* g_out,
                float* grad_x);

void conv_forward(const ConvShape& s, const float* in, const float* w, const float* b, float* out);
void conv_backward_input(const ConvShape& s, const float* w, const float* g_out, float* g_in);
void conv_backward_params(const ConvShape& s, const float* in, const float* g_out, float* row_partials,
                          float* g_w, float* g_b);
void relu_forward(float* x, std::size_t n);
void relu_backward(const float* y, float* g, std::size_t n);
void sigmoid_forward(const float* z, float* y, std::size_t n);
void sigmoid_backward(const float* y, float* g, std::size_t n);
void copy_window(const float* src, int channels, int width, int height, PixelWindow win, float* dst);
void add_window(const float* src, int channels, int width, int height, PixelWindow win, float* dst);

}  // namespace goris::ssf::cuda
