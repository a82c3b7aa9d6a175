// CUDA-GL interop for the viewport textures. Only CUDA's own GL interop header is used here (it brings
// GL/gl.h for GLuint/GL_TEXTURE_2D); no GL calls are made, so the editor's core-profile header stays out.
#include <cuda_gl_interop.h>

#include <string>
#include <unordered_map>

#include "core/compute/cuda_check.h"
#include "ui/gl/cuda_texture_interop.h"

namespace goris::ui {

namespace {

struct Registration {
  cudaGraphicsResource_t resource = nullptr;
  int width = 0, height = 0, channels = 0;
};

void unregister(Registration& r) {
  // Unregistering cannot be refused for a valid resource; an error here (context gone) is not worth a throw.
  if (r.resource) cudaGraphicsUnregisterResource(r.resource);
  r.resource = nullptr;
}

}  // namespace

struct CudaTextureInterop::Registrations {
  std::unordered_map<unsigned, Registration> by_texture;
};

CudaTextureInterop::CudaTextureInterop() : registrations_(std::make_unique<Registrations>()) {}

CudaTextureInterop::~CudaTextureInterop() {
  for (auto& [texture, r] : registrations_->by_texture) unregister(r);
}

void CudaTextureInterop::forget(unsigned texture) {
  const auto it = registrations_->by_texture.find(texture);
  if (it == registrations_->by_texture.end()) return;
  unregister(it->second);
  registrations_->by_texture.erase(it);
}

void CudaTextureInterop::copy(unsigned texture, int width, int height, int channels, const float* src) {
  if (texture == 0 || width <= 0 || height <= 0 || !(channels == 1 || channels == 2 || channels == 4))
    throw Error("CUDA-GL interop", "cannot copy " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                                       std::to_string(channels) + " floats into texture " + std::to_string(texture));
  Registration& r = registrations_->by_texture[texture];
  if (r.resource && (r.width != width || r.height != height || r.channels != channels)) unregister(r);
  if (!r.resource) {
    const cudaError_t e =
        cudaGraphicsGLRegisterImage(&r.resource, texture, GL_TEXTURE_2D, cudaGraphicsRegisterFlagsWriteDiscard);
    if (e != cudaSuccess) {
      r.resource = nullptr;
      registrations_->by_texture.erase(texture);
      cudaGetLastError();  // clear it, so that the next CUDA call does not report it again
      throw Error("CUDA-GL interop", "cannot register GL texture " + std::to_string(texture) +
                                         " with CUDA: " + cudaGetErrorString(e));
    }
    r.width = width;
    r.height = height;
    r.channels = channels;
  }
  GORIS_CUDA_CHECK(cudaGraphicsMapResources(1, &r.resource, 0));
  cudaArray_t array = nullptr;
  const size_t row = size_t(width) * size_t(channels) * sizeof(float);
  cudaError_t e = cudaGraphicsSubResourceGetMappedArray(&array, r.resource, 0, 0);
  if (e == cudaSuccess) e = cudaMemcpy2DToArray(array, 0, 0, src, row, row, size_t(height), cudaMemcpyDeviceToDevice);
  // Unmapped whatever happened, so that GL may use (or delete) the texture again.
  const cudaError_t unmap = cudaGraphicsUnmapResources(1, &r.resource, 0);
  if (e == cudaSuccess) e = unmap;
  if (e != cudaSuccess)
    throw Error("CUDA-GL interop", "copy into GL texture " + std::to_string(texture) + " failed: " +
                                       cudaGetErrorString(e));
}

}  // namespace goris::ui
