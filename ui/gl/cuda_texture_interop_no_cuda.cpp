// CUDA-GL interop in builds without nvcc: nothing is ever registered and a copy says why it cannot be done
// (FrameTextures then uploads from the host; such a build cannot hold CUDA images anyway).
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "ui/gl/cuda_texture_interop.h"

namespace goris::ui {

struct CudaTextureInterop::Registrations {};

CudaTextureInterop::CudaTextureInterop() = default;
CudaTextureInterop::~CudaTextureInterop() = default;

void CudaTextureInterop::copy(unsigned, int, int, int, const float*) {
  throw Error("CUDA-GL interop", "this build has no CUDA backend");
}
void CudaTextureInterop::forget(unsigned) {}

}  // namespace goris::ui
#endif
