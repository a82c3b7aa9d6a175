// CUDA twin of the deferred-shading drivers: the same shading_ops.h code on Device::CUDA.
#include "render/shading/shading_cuda.h"
#include "render/shading/shading_ops.h"

namespace goris::shading::cuda {

constexpr Device D = Device::CUDA;

ReflectionRaysT<float> make_rays(const Camera& cam, const SurfaceImagesT<float>& s, const ShadingSettings& st) {
  return ops::make_rays(D, cam, s, st);
}
void rays_backward(const Camera& cam, const SurfaceImagesT<float>& s, const ShadingSettings& st,
                   const std::uint32_t* pixels, std::size_t n, const float* dorigins, const float* ddirections,
                   const SurfaceGradsT<float>& g) {
  ops::rays_backward(D, cam, s, st, pixels, n, dorigins, ddirections, g);
}
void traced_to_images(std::size_t P, const std::uint32_t* pixels, std::size_t n, const float* color,
                      const float* alpha, const TracedImageSettings& ts, float* L, float* V) {
  ops::traced_to_images(D, P, pixels, n, color, alpha, ts, L, V);
}
void traced_to_images_backward(std::size_t P, const std::uint32_t* pixels, std::size_t n, const float* color,
                               const float* alpha, const TracedImageSettings& ts, const float* dL, const float* dV,
                               float* dcolor, float* dalpha) {
  ops::traced_to_images_backward(D, P, pixels, n, color, alpha, ts, dL, dV, dcolor, dalpha);
}
void shade(const Camera& cam, const SurfaceImagesT<float>& s, const float* L, const float* V,
           const envmap::CubeMipsT<float>& env, const ShadingSettings& st, float* color, float* glossy, float* ldir) {
  ops::shade(D, cam, s, L, V, env, st, color, glossy, ldir);
}
void shade_backward(const Camera& cam, const SurfaceImagesT<float>& s, const float* L, const float* V,
                    const envmap::CubeMipsT<float>& env, const ShadingSettings& st, const float* dcolor,
                    const SurfaceGradsT<float>& g, float* dL, float* dV, float* env_grad) {
  ops::shade_backward(D, cam, s, L, V, env, st, dcolor, g, dL, dV, env_grad);
}

}  // namespace goris::shading::cuda
