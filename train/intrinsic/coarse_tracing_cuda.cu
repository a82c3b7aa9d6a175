// CUDA twin of coarse tracing: the passes of coarse_tracing_ops.h instantiated for Device::CUDA (one thread
// per ray / pixel), synchronised and checked after each call.
#include "core/compute/cuda_check.h"
#include "train/intrinsic/coarse_tracing_cuda.h"
#include "train/intrinsic/coarse_tracing_ops.h"

namespace goris::coarse::cuda {

namespace {
void sync_and_check() { GORIS_CUDA_CHECK(cudaDeviceSynchronize()); }
}  // namespace

void select(const std::uint32_t* pixels, std::size_t n, int W, int H, const float* rs, int levels, int max_level,
            std::uint32_t seed, std::int32_t* lvl, std::uint32_t* keep) {
  coarse::select<Device::CUDA>(pixels, n, W, H, rs, levels, max_level, seed, lvl, keep);
  sync_and_check();
}
void difference(const std::uint32_t* a, const std::uint32_t* b, std::size_t n, std::uint32_t* out) {
  coarse::difference<Device::CUDA>(a, b, n, out);
  sync_and_check();
}
void gather(const std::uint32_t* pixels, const float* origins, const float* directions, std::size_t n,
            const std::uint32_t* keep, const std::uint32_t* slot, std::size_t offset, std::uint32_t* out_pixels,
            float* out_origins, float* out_directions) {
  coarse::gather<Device::CUDA>(pixels, origins, directions, n, keep, slot, offset, out_pixels, out_origins,
                               out_directions);
  sync_and_check();
}
void representative_distance(const std::uint32_t* pixels, std::size_t n, int W, int H, const std::uint32_t* keep,
                             const std::uint32_t* slot, const float* depth, const float* alpha, int block_level,
                             float extent, std::uint32_t* index, float* out) {
  coarse::representative_distance<Device::CUDA>(pixels, n, W, H, keep, slot, depth, alpha, block_level, extent,
                                                index, out);
  sync_and_check();
}
void mass(const std::uint32_t* pixels, std::size_t n, const std::uint32_t* keep, std::size_t P, float* out) {
  coarse::mass<Device::CUDA>(pixels, n, keep, P, out);
  sync_and_check();
}

}  // namespace goris::coarse::cuda
