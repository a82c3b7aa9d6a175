// Stand-ins for the CUDA shading drivers in builds without nvcc: a clear error instead of a link failure.
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/shading/shading_cuda.h"

namespace goris::shading::cuda {

namespace {
[[noreturn]] void no_cuda() { throw Error("shading", "CUDA device requested but this build has no CUDA backend"); }
}  // namespace

ReflectionRaysT<float> make_rays(const Camera&, const SurfaceImagesT<float>&, const ShadingSettings&) { no_cuda(); }
void rays_backward(const Camera&, const SurfaceImagesT<float>&, const ShadingSettings&, const std::uint32_t*,
                   std::size_t, const float*, const float*, const SurfaceGradsT<float>&) {
  no_cuda();
}
void traced_to_images(std::size_t, const std::uint32_t*, std::size_t, const float*, const float*,
                      const TracedImageSettings&, float*, float*) {
  no_cuda();
}
void traced_to_images_backward(std::size_t, const std::uint32_t*, std::size_t, const float*, const float*,
                               const TracedImageSettings&, const float*, const float*, float*, float*) {
  no_cuda();
}
void shade(const Camera&, const SurfaceImagesT<float>&, const float*, const float*, const envmap::CubeMipsT<float>&,
           const ShadingSettings&, float*, float*, float*) {
  no_cuda();
}
void shade_backward(const Camera&, const SurfaceImagesT<float>&, const float*, const float*,
                    const envmap::CubeMipsT<float>&, const ShadingSettings&, const float*, const SurfaceGradsT<float>&,
                    float*, float*, float*) {
  no_cuda();
}

}  // namespace goris::shading::cuda
#endif
