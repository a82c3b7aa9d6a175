// Stand-ins for the CUDA glue of the intrinsic renderer in builds without nvcc: a clear error instead of a
// link failure (only called for buffers on Device::CUDA, which such a build cannot allocate).
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/intrinsic/intrinsic_glue.h"

namespace goris::intrinsic_glue::cuda {

namespace {
[[noreturn]] void no_cuda() { throw Error("intrinsic renderer", "CUDA device requested but this build has no CUDA backend"); }
}  // namespace

void emit_weights(const float*, int, int, std::size_t, const float*, bool, float*, std::uint8_t*) { no_cuda(); }
void net_input(const float*, const float*, const float*, const float*, std::size_t, float, float*) { no_cuda(); }
void add_emit_grads(const float*, const std::uint8_t*, std::size_t, int, int, float*) { no_cuda(); }
void transparent_logits(const float*, const float*, std::size_t, float, float*) { no_cuda(); }

}  // namespace goris::intrinsic_glue::cuda
#endif
