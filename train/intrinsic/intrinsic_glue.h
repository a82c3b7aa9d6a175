#pragma once
// The intrinsic renderer's per-element glue (intrinsic_glue_ops.h) on the device of its buffers: the CPU
// runs the ops directly, CUDA through intrinsic_glue_cuda.cu (a build without CUDA throws goris::Error).
#include <cstddef>
#include <cstdint>

#include "core/compute/device.h"

namespace goris::intrinsic_glue {

void emit_weights(Device d, const float* extras, int stride, int region, std::size_t n, const float* override_w,
                  bool or_region, float* emit, std::uint8_t* region_emits);
void net_input(Device d, const float* roughness, const float* distance, const float* depth, const float* alpha,
               std::size_t hw, float extent, float* in);
void add_emit_grads(Device d, const float* demit, const std::uint8_t* region_emits, std::size_t n, int stride,
                    int region, float* grad_extras);
void transparent_logits(Device d, const float* logits, const float* emit, std::size_t n, float threshold, float* out);

namespace cuda {
void emit_weights(const float* extras, int stride, int region, std::size_t n, const float* override_w, bool or_region,
                  float* emit, std::uint8_t* region_emits);
void net_input(const float* roughness, const float* distance, const float* depth, const float* alpha, std::size_t hw,
               float extent, float* in);
void add_emit_grads(const float* demit, const std::uint8_t* region_emits, std::size_t n, int stride, int region,
                    float* grad_extras);
void transparent_logits(const float* logits, const float* emit, std::size_t n, float threshold, float* out);
}  // namespace cuda

}  // namespace goris::intrinsic_glue
