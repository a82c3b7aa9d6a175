#pragma once
// Deferred shading of the intrinsic model (docs/design/maths.md, Shading; paper Sec. 3.2, supplementary
// S1.1-S1.2), forward and backward, per pixel on the G-buffer:
//
//   C = D + (1 - M) G,   G = F (L_ind' + L_dir' V'),   F = F0 + (1 - F0)(1 - n . omega_r)^5
//
// on surface pixels (alpha > min_alpha; C = D elsewhere). One iteration:
//
//   auto s    = surface_from_gbuffer(gbuf, channels);
//   auto rays = make_reflection_rays(cam, s, settings, dev);     // glossy pixels only
//   tracer.trace({rays.origins, rays.directions, rays.count}, {colour, depth, alpha});
//   traced_to_images(rays, W, H, colour, alpha, tis, L, V);      // (or the screen-space filter's L', V')
//   env.update();  auto out = shade(cam, s, L, V, env.mips(), settings, dev);
//   -- backward, in reverse --
//   shade_backward(..., dC, grads, dL, dV, env.mip_grads(), dev);  env.backward();
//   traced_to_images_backward(...); tracer.backward(...); reflection_rays_backward(...);
//
// All image gradients into the G-buffer accumulate (+=). Every entry point throws goris::Error for images of
// the wrong size, null planes, a camera that does not match, non-finite inputs (checked on the CPU backend)
// and CUDA requests in builds without CUDA (or in double precision, which is CPU-only).
#include "core/compute/device.h"
#include "core/io/camera.h"
#include "render/envmap/cube_map_math.h"
#include "render/raster/raster_types.h"
#include "render/shading/shading_types.h"

namespace goris {

// Where the material channels sit among the G-buffer's extras (F0 takes three consecutive channels).
struct MaterialChannels {
  int region = 0;
  int f0 = 1;
  int roughness = 4;
};

// A view of the G-buffer's colour, alpha, depth, normal and the material extras; checks the channel indices.
template <class T>
SurfaceImagesT<T> surface_from_gbuffer(const GBufferT<T>& gbuffer, const MaterialChannels& channels);

// One reflection ray per glossy pixel (alpha > min_alpha, M < glossy_max_region, depth > 0): origin
// x + ray_offset omega_r with x = camera centre + (depth / alpha) R^T (x_n, y_n, 1), direction omega_r.
template <class T>
ReflectionRaysT<T> make_reflection_rays(const Camera& camera, const SurfaceImagesT<T>& surface,
                                        const ShadingSettings& settings, Device device);

// dL/d(ray origins) and dL/d(ray directions) ([n][3] each, either may be null) -> grads.depth, .alpha,
// .normal (+=) of the rays' pixels.
template <class T>
void reflection_rays_backward(const Camera& camera, const SurfaceImagesT<T>& surface, const ShadingSettings& settings,
                              const ReflectionRaysT<T>& rays, const T* dorigins, const T* ddirections,
                              const SurfaceGradsT<T>& grads, Device device);

// Traced colour [n][3] and alpha [n] of the rays -> L_ind [3][H][W] and V [H][W] (reallocated); pixels
// without a ray get L = 0, V = 1. With settings.divide_opaque, rays with alpha >= opaque_alpha give
// L = colour / alpha and V = 0 (the authors' normalisation); otherwise L = colour, V = 1 - alpha.
template <class T>
void traced_to_images(const ReflectionRaysT<T>& rays, int width, int height, const Buffer<T>& color,
                      const Buffer<T>& alpha, const TracedImageSettings& settings, Buffer<T>& L, Buffer<T>& V);

// Backward of traced_to_images: dcolor [n][3], dalpha [n] (reallocated, written). dV may be empty (zero).
template <class T>
void traced_to_images_backward(const ReflectionRaysT<T>& rays, int width, int height, const Buffer<T>& color,
                               const Buffer<T>& alpha, const TracedImageSettings& settings, const Buffer<T>& dL,
                               const Buffer<T>& dV, Buffer<T>& dcolor, Buffer<T>& dalpha);

template <class T>
struct ShadeOutputsT {
  Buffer<T> color;         // C [3][H][W]
  Buffer<T> glossy;        // G [3][H][W] (before the (1 - M) weight), only with maps
  Buffer<T> env_radiance;  // L_dir' [3][H][W], only with maps
};

// The shading combine. L, V: L_ind' [3][H][W] and V' [H][W] (from traced_to_images or the filter); env: a
// prefiltered cube map on `device` (EnvironmentMap::mips()), looked up at omega_r with the roughness.
template <class T>
ShadeOutputsT<T> shade(const Camera& camera, const SurfaceImagesT<T>& surface, const Buffer<T>& L, const Buffer<T>& V,
                       const envmap::CubeMipsT<T>& env, const ShadingSettings& settings, Device device,
                       bool maps = false);

// Backward of shade given dL/dC [3][H][W]: grads += dL/d(surface) (colour, alpha, normal, region, F0,
// roughness; depth has no gradient here: it only moves the ray origins), dL / dV reallocated and written,
// env_grad (EnvironmentMap::mip_grads(), may be null) += dL/dtexels.
template <class T>
void shade_backward(const Camera& camera, const SurfaceImagesT<T>& surface, const Buffer<T>& L, const Buffer<T>& V,
                    const envmap::CubeMipsT<T>& env, const ShadingSettings& settings, const Buffer<T>& dcolor,
                    const SurfaceGradsT<T>& grads, Buffer<T>& dL, Buffer<T>& dV, T* env_grad, Device device);

using ShadeOutputs = ShadeOutputsT<float>;

}  // namespace goris
