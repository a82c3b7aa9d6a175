#pragma once
// How a CUDA DisplayFrame keeps its images on the device: the planar [C][H][W] G-buffer channels become
// interleaved [H][W][C] textures' worth of floats, on whichever device the G-buffer lives. Three-channel
// maps are padded to four (alpha 1, what GL reads for an RGB texture) because CUDA-GL interop cannot
// register three-component textures. The passes run on the CPU (TBB) or on CUDA (frame_layout_cuda.cu).
#include <cstddef>

#include "core/compute/device.h"

namespace goris::ui::frame_layout {

// Channels of the texture a map of `channels` is copied into through interop (3 -> 4, others as is).
constexpr int interop_channels(int channels) { return channels == 3 ? 4 : channels; }

// out[p * stride + at + c] = planar[(first + c) * hw + p] for c < count.
void interleave(Device d, const float* planar, int first, int count, std::size_t hw, float* out, int stride, int at);
// out[p * stride + at] = value.
void fill(Device d, float* out, std::size_t hw, int stride, int at, float value);
// out[p * stride + 0..2] = the unit camera-space normal where alpha[p] >= min_alpha and the (unnormalised)
// normal is not null, else 0 (as the host frame does).
void unit_normals(Device d, const float* normal, const float* alpha, std::size_t hw, float min_alpha, float* out,
                  int stride);
// out[i] = in[i] clamped to [0, 1].
void clamp_unit(Device d, const float* in, std::size_t n, float* out);

}  // namespace goris::ui::frame_layout
