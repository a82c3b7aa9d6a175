// CUDA twin of the intrinsic renderer's glue: the ops of intrinsic_glue_ops.h on Device::CUDA, checked after
// each launch.
#include "core/compute/cuda_check.h"
#include "train/intrinsic/intrinsic_glue.h"
#include "train/intrinsic/intrinsic_glue_ops.h"

namespace goris::intrinsic_glue::cuda {

namespace {
void check() { GORIS_CUDA_CHECK(cudaGetLastError()); }
}  // namespace

void emit_weights(const float* extras, int stride, int region, std::size_t n, const float* override_w, bool or_region,
                  float* emit, std::uint8_t* region_emits) {
  intrinsic_glue::emit_weights<Device::CUDA>(extras, stride, region, n, override_w, or_region, emit, region_emits);
  check();
}
void net_input(const float* roughness, const float* distance, const float* depth, const float* alpha, std::size_t hw,
               float extent, float* in) {
  intrinsic_glue::net_input<Device::CUDA>(roughness, distance, depth, alpha, hw, extent, in);
  check();
}
void add_emit_grads(const float* demit, const std::uint8_t* region_emits, std::size_t n, int stride, int region,
                    float* grad_extras) {
  intrinsic_glue::add_emit_grads<Device::CUDA>(demit, region_emits, n, stride, region, grad_extras);
  check();
}
void transparent_logits(const float* logits, const float* emit, std::size_t n, float threshold, float* out) {
  intrinsic_glue::transparent_logits<Device::CUDA>(logits, emit, n, threshold, out);
  check();
}

}  // namespace goris::intrinsic_glue::cuda
