#pragma once
// Copies images that live on the CUDA device straight into GL textures (CUDA-GL interop), without a trip
// through host memory: each texture is registered with CUDA once (again when its storage changes), mapped
// for the copy and unmapped. Call on the thread whose GL context owns the textures. A build without CUDA
// holds no CUDA images: there nothing is ever registered and every copy throws goris::Error.
#include <memory>

#include "core/util/error.h"

namespace goris::ui {

class CudaTextureInterop {
 public:
#ifdef GORIS_WITH_CUDA
  CudaTextureInterop();
  ~CudaTextureInterop();  // unregisters every texture (their GL context must still be current)
#else
  CudaTextureInterop() = default;
#endif
  CudaTextureInterop(const CudaTextureInterop&) = delete;
  CudaTextureInterop& operator=(const CudaTextureInterop&) = delete;

  // Copies width x height pixels of `channels` (1, 2 or 4: CUDA cannot register 3-component textures)
  // interleaved floats at the CUDA device pointer `src` into GL texture `texture`, whose storage must be
  // exactly that (GL_R32F / GL_RG32F / GL_RGBA32F). Throws goris::Error when CUDA refuses (e.g. the GL
  // context is not on the CUDA device's driver, as under Mesa).
  void copy(unsigned texture, int width, int height, int channels, const float* src);
  // Drops the registration of `texture`, before its storage is re-specified or it is deleted.
  void forget(unsigned texture);

#ifdef GORIS_WITH_CUDA
 private:
  struct Registrations;
  std::unique_ptr<Registrations> registrations_;
#endif
};

#ifndef GORIS_WITH_CUDA
inline void CudaTextureInterop::copy(unsigned, int, int, int, const float*) {
  throw Error("CUDA-GL interop", "this build has no CUDA backend");
}
inline void CudaTextureInterop::forget(unsigned) {}
#endif

}  // namespace goris::ui
