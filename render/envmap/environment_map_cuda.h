#pragma once
// The CUDA side of EnvironmentMap (environment_map_cuda.cu): the cube_map_ops.h drivers run on
// Device::CUDA. Without CUDA the call throws goris::Error (GORIS_CUDA_CALL).
#include <cstddef>

#include "render/envmap/cube_map_math.h"

namespace goris::envmap::cuda {

// chain level 0 = exp(params), levels 1.. prefiltered.
void build_chain(const float* params, float* chain, float* scratch, int R, int L);
// param_grad += (prefilter adjoint of chain_grad at level 0) * chain level 0; chain_grad is overwritten.
void backward_chain(float* chain_grad, float* scratch, const float* chain, float* param_grad, int R, int L);
void lookup(const CubeMipsT<float>& mips, const float* dirs, const float* roughness, std::size_t n, float* out);
void lookup_backward(const CubeMipsT<float>& mips, const float* dirs, const float* roughness, const float* dout,
                     std::size_t n, float* chain_grad, float* ddirs, float* droughness);

}  // namespace goris::envmap::cuda
