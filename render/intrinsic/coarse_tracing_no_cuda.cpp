// Stand-ins for the CUDA passes of coarse tracing in builds without nvcc: a clear error instead of a link
// failure (the driver only calls them for buffers on Device::CUDA, which such a build cannot allocate).
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/intrinsic/coarse_tracing_cuda.h"

namespace goris::coarse::cuda {

namespace {
[[noreturn]] void no_cuda() { throw Error("coarse tracing", "CUDA device requested but this build has no CUDA backend"); }
}  // namespace

void select(const std::uint32_t*, std::size_t, int, int, const float*, int, int, std::uint32_t, std::int32_t*,
            std::uint32_t*) {
  no_cuda();
}
void difference(const std::uint32_t*, const std::uint32_t*, std::size_t, std::uint32_t*) { no_cuda(); }
void gather(const std::uint32_t*, const float*, const float*, std::size_t, const std::uint32_t*, const std::uint32_t*,
            std::size_t, std::uint32_t*, float*, float*) {
  no_cuda();
}
void representative_distance(const std::uint32_t*, std::size_t, int, int, const std::uint32_t*, const std::uint32_t*,
                             const float*, const float*, int, float, std::uint32_t*, float*) {
  no_cuda();
}
void mass(const std::uint32_t*, std::size_t, const std::uint32_t*, std::size_t, float*) { no_cuda(); }

}  // namespace goris::coarse::cuda
#endif
