#pragma once
// Copies images that live on the CUDA device straight into GL textures (CUDA-GL interop), without a trip
// through host memory: each texture is registered with CUDA once (again when its storage changes), mapped
// for the copy and unmapped. Call on the thread whose GL context owns the textures. In a build without
// CUDA (cuda_texture_interop_no_cuda.cpp) every copy throws goris::Error.
#include <memory>

namespace goris::ui {

class CudaTextureInterop {
 public:
  CudaTextureInterop();
  ~CudaTextureInterop();  // unregisters every texture (their GL context must still be current)
  CudaTextureInterop(const CudaTextureInterop&) = delete;
  CudaTextureInterop& operator=(const CudaTextureInterop&) = delete;

  // Copies width x height pixels of `channels` (1, 2 or 4: CUDA cannot register 3-component textures)
  // interleaved floats at the CUDA device pointer `src` into GL texture `texture`, whose storage must be
  // exactly that (GL_R32F / GL_RG32F / GL_RGBA32F). Throws goris::Error when CUDA refuses (e.g. the GL
  // context is not on the CUDA device's driver, as under Mesa).
  void copy(unsigned texture, int width, int height, int channels, const float* src);
  // Drops the registration of `texture`, before its storage is re-specified or it is deleted.
  void forget(unsigned texture);

 private:
  struct Registrations;
  std::unique_ptr<Registrations> registrations_;
};

}  // namespace goris::ui
