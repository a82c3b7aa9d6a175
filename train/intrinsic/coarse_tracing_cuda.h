#pragma once
// The CUDA side of coarse tracing (coarse_tracing_cuda.cu): the coarse_tracing_ops.h passes on Device::CUDA.
// Without CUDA the call throws goris::Error (GORIS_CUDA_CALL).
#include <cstddef>
#include <cstdint>

namespace goris::coarse::cuda {

void select(const std::uint32_t* pixels, std::size_t n, int W, int H, const float* rs, int levels, int max_level,
            std::uint32_t seed, std::int32_t* lvl, std::uint32_t* keep);
void difference(const std::uint32_t* a, const std::uint32_t* b, std::size_t n, std::uint32_t* out);
void gather(const std::uint32_t* pixels, const float* origins, const float* directions, std::size_t n,
            const std::uint32_t* keep, const std::uint32_t* slot, std::size_t offset, std::uint32_t* out_pixels,
            float* out_origins, float* out_directions);
void representative_distance(const std::uint32_t* pixels, std::size_t n, int W, int H, const std::uint32_t* keep,
                             const std::uint32_t* slot, const float* depth, const float* alpha, int block_level,
                             float extent, std::uint32_t* index, float* out);
void mass(const std::uint32_t* pixels, std::size_t n, const std::uint32_t* keep, std::size_t P, float* out);

}  // namespace goris::coarse::cuda
