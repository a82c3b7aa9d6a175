#include "train/intrinsic/intrinsic_glue.h"

#include "core/compute/cuda_dispatch.h"
#include "train/intrinsic/intrinsic_glue_ops.h"

namespace goris::intrinsic_glue {

namespace {
constexpr const char* kWho = "intrinsic renderer";
}  // namespace

void emit_weights(Device d, const float* extras, int stride, int region, std::size_t n, const float* override_w,
                  bool or_region, float* emit, std::uint8_t* region_emits) {
  if (d == Device::CUDA)
    return GORIS_CUDA_CALL(kWho,
                           cuda::emit_weights(extras, stride, region, n, override_w, or_region, emit, region_emits));
  emit_weights<Device::CPU>(extras, stride, region, n, override_w, or_region, emit, region_emits);
}

void net_input(Device d, const float* roughness, const float* distance, const float* depth, const float* alpha,
               std::size_t hw, float extent, float* in) {
  if (d == Device::CUDA)
    return GORIS_CUDA_CALL(kWho, cuda::net_input(roughness, distance, depth, alpha, hw, extent, in));
  net_input<Device::CPU>(roughness, distance, depth, alpha, hw, extent, in);
}

void add_emit_grads(Device d, const float* demit, const std::uint8_t* region_emits, std::size_t n, int stride,
                    int region, float* grad_extras) {
  if (d == Device::CUDA)
    return GORIS_CUDA_CALL(kWho, cuda::add_emit_grads(demit, region_emits, n, stride, region, grad_extras));
  add_emit_grads<Device::CPU>(demit, region_emits, n, stride, region, grad_extras);
}

void transparent_logits(Device d, const float* logits, const float* emit, std::size_t n, float threshold, float* out) {
  if (d == Device::CUDA) return GORIS_CUDA_CALL(kWho, cuda::transparent_logits(logits, emit, n, threshold, out));
  transparent_logits<Device::CPU>(logits, emit, n, threshold, out);
}

}  // namespace goris::intrinsic_glue
