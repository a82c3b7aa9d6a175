#pragma once
// The per-element steps between the intrinsic renderer's stages - each Gaussian's emit weight and its
// gradient, the roughness net's input planes - written once on parallel_for for both backends, so that on
// CUDA a frame's data stays on the GPU (these steps used to run on the host with a download and an upload
// each, a cost that grows with the resolution and the Gaussian count). intrinsic_glue.cpp instantiates them
// on the CPU, intrinsic_glue_cuda.cu on CUDA.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/compute/parallel_for.h"

namespace goris::intrinsic_glue {

// emit[i] = Gaussian i's region weight M = extras[i * stride + region], or with an override (null: none)
// the override where it wins: with or_region, emit = M where M >= override (M keeps its gradient), else
// the override. region_emits[i] = 1 where emit is M.
template <Device D>
void emit_weights(const float* extras, int stride, int region, std::size_t n, const float* override_w, bool or_region,
                  float* emit, std::uint8_t* region_emits) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    const float m = extras[i * std::size_t(stride) + std::size_t(region)];
    const bool is_m = !override_w || (or_region && m >= override_w[i]);
    region_emits[i] = is_m ? 1 : 0;
    emit[i] = is_m ? m : override_w[i];
  });
}

// The net's input planes [3][hw]: roughness, the traced hit distance, and the inverse view depth
// extent * alpha / depth (capped at 100; 0 off the surface), distances in scene extents.
template <Device D>
void net_input(const float* roughness, const float* distance, const float* depth, const float* alpha, std::size_t hw,
               float extent, float* in) {
  parallel_for(D, hw, [=] GORIS_HD(std::size_t p) {
    in[p] = roughness[p];
    in[hw + p] = distance[p];
    const float inv = depth[p] > 1e-6f && alpha[p] > 1e-4f ? extent * alpha[p] / depth[p] : 0.0f;
    in[2 * hw + p] = inv < 100.0f ? inv : 100.0f;
  }, 4096);
}

// grad_extras[i * stride + region] += demit[i] where region_emits[i] (null: everywhere): dL/d(emit) is
// dL/dM where the emit weight is M.
template <Device D>
void add_emit_grads(const float* demit, const std::uint8_t* region_emits, std::size_t n, int stride, int region,
                    float* grad_extras) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    if (!region_emits || region_emits[i]) grad_extras[i * std::size_t(stride) + std::size_t(region)] += demit[i];
  });
}

// The opacity logits the reflection rays see (intrinsic_trace_glossy_transparent): a Gaussian whose emit
// weight is below `threshold` gets a logit whose opacity is 0, so the tracer gives it an empty box and no
// ray ever hits it (nor sends it a gradient); the others keep theirs.
constexpr float kTransparentLogit = -1e4f;  // sigmoid = 0 in float

template <Device D>
void transparent_logits(const float* logits, const float* emit, std::size_t n, float threshold, float* out) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) { out[i] = emit[i] < threshold ? kTransparentLogit : logits[i]; });
}

}  // namespace goris::intrinsic_glue
