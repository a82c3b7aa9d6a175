#pragma once
// The CUDA side of deferred shading (shading_cuda.cu): the shading_ops.h drivers on Device::CUDA, float only.
// Without CUDA the call throws goris::Error (GORIS_CUDA_CALL).
#include <cstdint>

#include "core/io/camera.h"
#include "render/envmap/cube_map_math.h"
#include "render/shading/shading_types.h"

namespace goris::shading::cuda {

ReflectionRaysT<float> make_rays(const Camera& cam, const SurfaceImagesT<float>& s, const ShadingSettings& st);
void rays_backward(const Camera& cam, const SurfaceImagesT<float>& s, const ShadingSettings& st,
                   const std::uint32_t* pixels, std::size_t n, const float* dorigins, const float* ddirections,
                   const SurfaceGradsT<float>& g);
void traced_to_images(std::size_t P, const std::uint32_t* pixels, std::size_t n, const float* color,
                      const float* alpha, const TracedImageSettings& ts, float* L, float* V);
void traced_to_images_backward(std::size_t P, const std::uint32_t* pixels, std::size_t n, const float* color,
                               const float* alpha, const TracedImageSettings& ts, const float* dL, const float* dV,
                               float* dcolor, float* dalpha);
void shade(const Camera& cam, const SurfaceImagesT<float>& s, const float* L, const float* V,
           const envmap::CubeMipsT<float>& env, const ShadingSettings& st, float* color, float* glossy, float* ldir);
void shade_backward(const Camera& cam, const SurfaceImagesT<float>& s, const float* L, const float* V,
                    const envmap::CubeMipsT<float>& env, const ShadingSettings& st, const float* dcolor,
                    const SurfaceGradsT<float>& g, float* dL, float* dV, float* env_grad);

}  // namespace goris::shading::cuda
