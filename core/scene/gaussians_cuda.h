#pragma once
// CUDA entry points of the scene model's kernels (gaussians_cuda.cu), called through GORIS_CUDA_CALL.
#include <cstddef>

namespace goris::detail {
void extras_forward_cuda(const float* logits, float* activated, size_t n);
void extras_backward_cuda(const float* activated, float* activated_grad, float* logit_grad, size_t n);
void diffuse_from_sh_dc_cuda(const float* sh, int sh_width, float* extra_logits, int extras_width, int first, size_t n);
}  // namespace goris::detail
