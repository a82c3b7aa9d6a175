// Stand-ins for the CUDA frame layout passes in builds without nvcc: a clear error instead of a link failure
// (they are only called for buffers on Device::CUDA, which such a build cannot allocate).
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "ui/display/frame_layout_ops.h"

namespace goris::ui::frame_layout::cuda {

namespace {
[[noreturn]] void no_cuda() { throw Error("display", "CUDA frame requested but this build has no CUDA backend"); }
}  // namespace

void interleave(const float*, int, int, std::size_t, float*, int, int) { no_cuda(); }
void fill(float*, std::size_t, int, int, float) { no_cuda(); }
void unit_normals(const float*, const float*, std::size_t, float, float*, int) { no_cuda(); }
void clamp_unit(const float*, std::size_t, float*) { no_cuda(); }

}  // namespace goris::ui::frame_layout::cuda
#endif
