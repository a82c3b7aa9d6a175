// Stand-ins for the CUDA glossy filter and roughness net in builds without nvcc: a clear error instead of a
// link failure (the drivers only call them for buffers on Device::CUDA, which such a build cannot allocate).
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/ssf/ssf_cuda.h"

namespace goris::ssf::cuda {

namespace {
[[noreturn]] void no_cuda() { throw Error("glossy filter", "CUDA device requested but this build has no CUDA backend"); }
}  // namespace

void normalise_normals(const float*, float*, std::size_t) { no_cuda(); }
void build_levels(const PyramidPtrs<float>&) { no_cuda(); }
void sample_all(const PyramidPtrs<float>&, const float*, float*) { no_cuda(); }
void backward_rs(const PyramidPtrs<float>&, const float*, const float*, float*) { no_cuda(); }
void backward_x(const PyramidPtrs<float>&, const PyramidPtrs<float>&, const float*, const float*, float*) { no_cuda(); }
void conv_forward(const ConvShape&, const float*, const float*, const float*, float*) { no_cuda(); }
void conv_backward_input(const ConvShape&, const float*, const float*, float*) { no_cuda(); }
void conv_backward_params(const ConvShape&, const float*, const float*, float*, float*, float*) { no_cuda(); }
void relu_forward(float*, std::size_t) { no_cuda(); }
void relu_backward(const float*, float*, std::size_t) { no_cuda(); }
void sigmoid_forward(const float*, float*, std::size_t) { no_cuda(); }
void sigmoid_backward(const float*, float*, std::size_t) { no_cuda(); }

}  // namespace goris::ssf::cuda
#endif
