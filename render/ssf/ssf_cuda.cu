// CUDA twin of the glossy filter and the roughness net: the passes of pyramid_passes.h and conv_passes.h
// instantiated for Device::CUDA (one thread per pixel / texel), synchronised and checked after each call.
#include "core/compute/cuda_check.h"
#include "render/ssf/ssf_cuda.h"

namespace goris::ssf::cuda {

namespace {
void sync_and_check() { GORIS_CUDA_CHECK(cudaDeviceSynchronize()); }
}  // namespace

void normalise_normals(const float* n_in, float* n_out, std::size_t plane) {
  ssf::normalise_normals<Device::CUDA>(n_in, n_out, plane);
  sync_and_check();
}
void build_levels(const PyramidPtrs<float>& P) {
  ssf::build_levels<Device::CUDA>(P);
  sync_and_check();
}
void sample_all(const PyramidPtrs<float>& P, const float* rs, float* out) {
  ssf::sample_all<Device::CUDA>(P, rs, out);
  sync_and_check();
}
void backward_rs(const PyramidPtrs<float>& P, const float* rs, const float* g_out, float* grad_rs) {
  ssf::backward_rs<Device::CUDA>(P, rs, g_out, grad_rs);
  sync_and_check();
}
void backward_x(const PyramidPtrs<float>& P, const PyramidPtrs<float>& scratch, const float* rs, const float* g_out,
                float* grad_x) {
  ssf::backward_x<Device::CUDA>(P, scratch, rs, g_out, grad_x);
  sync_and_check();
}

void conv_forward(const ConvShape& s, const float* in, const float* w, const float* b, float* out) {
  ssf::conv_forward<Device::CUDA>(s, in, w, b, out);
  sync_and_check();
}
void conv_backward_input(const ConvShape& s, const float* w, const float* g_out, float* g_in) {
  ssf::conv_backward_input<Device::CUDA>(s, w, g_out, g_in);
  sync_and_check();
}
void conv_backward_params(const ConvShape& s, const float* in, const float* g_out, float* row_partials, float* g_w,
                          float* g_b) {
  ssf::conv_backward_params<Device::CUDA>(s, in, g_out, row_partials, g_w, g_b);
  sync_and_check();
}
void relu_forward(float* x, std::size_t n) {
  ssf::relu_forward<Device::CUDA>(x, n);
  sync_and_check();
}
void relu_backward(const float* y, float* g, std::size_t n) {
  ssf::relu_backward<Device::CUDA>(y, g, n);
  sync_and_check();
}
void sigmoid_forward(const float* z, float* y, std::size_t n) {
  ssf::sigmoid_forward<Device::CUDA>(z, y, n);
  sync_and_check();
}
void sigmoid_backward(const float* y, float* g, std::size_t n) {
  ssf::sigmoid_backward<Device::CUDA>(y, g, n);
  sync_and_check();
}

void copy_window(const float* src, int channels, int width, int height, PixelWindow win, float* dst) {
  ssf::window_pass<Device::CUDA, WindowOp::CopyOut>(src, channels, width, height, win, dst);
  sync_and_check();
}
void add_window(const float* src, int channels, int width, int height, PixelWindow win, float* dst) {
  ssf::window_pass<Device::CUDA, WindowOp::AddIn>(dst, channels, width, height, win, src);
  sync_and_check();
}

}  // namespace goris::ssf::cuda
