// CUDA twin of the scene model's per-element kernels (maths in gaussian_kernels.h).
#include "core/compute/parallel_for.h"
#include "core/scene/gaussian_kernels.h"
#include "core/scene/gaussians_cuda.h"

namespace goris::detail {

void extras_forward_cuda(const float* logits, float* activated, size_t n) {
  parallel_for(Device::CUDA, n, [=] __device__(size_t i) { kernels::extras_forward(logits, activated, i); });
}

void extras_backward_cuda(const float* activated, float* activated_grad, float* logit_grad, size_t n) {
  parallel_for(Device::CUDA, n,
               [=] __device__(size_t i) { kernels::extras_backward(activated, activated_grad, logit_grad, i); });
}

void diffuse_from_sh_dc_cuda(const float* sh, int sh_width, float* extra_logits, int extras_width, int first, size_t n) {
  parallel_for(Device::CUDA, n, [=] __device__(size_t i) {
    kernels::diffuse_from_sh_dc(sh, sh_width, extra_logits, extras_width, first, i);
  });
}

}  // namespace goris::detail
