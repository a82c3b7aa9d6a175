// CUDA twin of the EnvironmentMap drivers: the same cube_map_ops.h code on Device::CUDA.
#include "render/envmap/cube_map_ops.h"
#include "render/envmap/environment_map_cuda.h"

namespace goris::envmap::cuda {

void build_chain(const float* params, float* chain, float* scratch, int R, int L) {
  ops::activate(Device::CUDA, params, chain, std::size_t(6) * R * R * 3);
  ops::prefilter(Device::CUDA, chain, scratch, R, L);
}

void backward_chain(float* chain_grad, float* scratch, const float* chain, float* param_grad, int R, int L) {
  ops::prefilter_adjoint(Device::CUDA, chain_grad, scratch, R, L);
  ops::activate_backward(Device::CUDA, chain, chain_grad, param_grad, std::size_t(6) * R * R * 3);
}

void lookup(const CubeMipsT<float>& mips, const float* dirs, const float* roughness, std::size_t n, float* out) {
  ops::lookup(Device::CUDA, mips, dirs, roughness, n, out);
}

void lookup_backward(const CubeMipsT<float>& mips, const float* dirs, const float* roughness, const float* dout,
                     std::size_t n, float* chain_grad, float* ddirs, float* droughness) {
  ops::lookup_backward(Device::CUDA, mips, dirs, roughness, dout, n, chain_grad, ddirs, droughness);
}

}  // namespace goris::envmap::cuda
