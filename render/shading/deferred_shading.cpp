// Public entry points of deferred shading: validate, then run shading_ops.h on the CPU or its CUDA twin.
#include "render/shading/deferred_shading.h"

#include <type_traits>

#include "core/compute/cuda_dispatch.h"
#include "render/shading/shading_checks.h"
#include "render/shading/shading_cuda.h"
#include "render/shading/shading_ops.h"

namespace goris {

namespace {

using namespace shading;

// CUDA runs in float only; double exists for the CPU gradient tests.
template <class T>
bool on_cuda(const char* who, Device d) {
  if (d != Device::CUDA) return false;
  if constexpr (!std::is_same_v<T, float>) throw Error(who, "double precision runs on the CPU only");
  return true;
}

}  // namespace

template <class T>
SurfaceImagesT<T> surface_from_gbuffer(const GBufferT<T>& g, const MaterialChannels& ch) {
  const char* who = "shading";
  const std::size_t P = g.pixels();
  if (P == 0) throw Error(who, "G-buffer is empty");
  auto need = [&](int c, int count, const char* name) {
    if (c < 0 || c + count > g.n_extras)
      throw Error(who, std::string(name) + " channel " + std::to_string(c) + " is outside the G-buffer's " +
                           std::to_string(g.n_extras) + " extra channels");
  };
  need(ch.region, 1, "region weight");
  need(ch.f0, 3, "F0");
  need(ch.roughness, 1, "roughness");
  if (g.color.size() != 3 * P || g.alpha.size() != P || g.depth.size() != P || g.normal.size() != 3 * P ||
      g.extras.size() != std::size_t(g.n_extras) * P)
    throw Error(who, "G-buffer planes do not match its " + std::to_string(g.width) + "x" + std::to_string(g.height) +
                         " size");
  SurfaceImagesT<T> s;
  s.width = g.width;
  s.height = g.height;
  s.color = g.color.data();
  s.alpha = g.alpha.data();
  s.depth = g.depth.data();
  s.normal = g.normal.data();
  s.region = g.extras.data() + std::size_t(ch.region) * P;
  s.f0 = g.extras.data() + std::size_t(ch.f0) * P;
  s.roughness = g.extras.data() + std::size_t(ch.roughness) * P;
  return s;
}

template <class T>
ReflectionRaysT<T> make_reflection_rays(const Camera& cam, const SurfaceImagesT<T>& s, const ShadingSettings& st,
                                        Device d) {
  const char* who = "reflection rays";
  check_settings(who, st);
  check_camera(who, cam, s.width, s.height);
  check_surface(who, s, d);
  if (on_cuda<T>(who, d)) {
    if constexpr (std::is_same_v<T, float>) return GORIS_CUDA_CALL("shading", shading::cuda::make_rays(cam, s, st));
  }
  return ops::make_rays(Device::CPU, cam, s, st);
}

template <class T>
void reflection_rays_backward(const Camera& cam, const SurfaceImagesT<T>& s, const ShadingSettings& st,
                              const ReflectionRaysT<T>& rays, const T* dorigins, const T* ddirections,
                              const SurfaceGradsT<T>& g, Device d) {
  const char* who = "reflection rays backward";
  check_settings(who, st);
  check_camera(who, cam, s.width, s.height);
  check_surface(who, s, d);
  check_buffer(who, rays.pixels, rays.count, d, "ray pixel list");
  if (rays.count == 0) return;
  if (on_cuda<T>(who, d)) {
    if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL("shading", shading::cuda::rays_backward(cam, s, st, rays.pixels.data(), rays.count, dorigins,
                                                              ddirections, g));
    return;
  }
  ops::rays_backward(Device::CPU, cam, s, st, rays.pixels.data(), rays.count, dorigins, ddirections, g);
}

template <class T>
void traced_to_images(const ReflectionRaysT<T>& rays, int width, int height, const Buffer<T>& color,
                      const Buffer<T>& alpha, const TracedImageSettings& ts, Buffer<T>& L, Buffer<T>& V) {
  const char* who = "traced images";
  if (width <= 0 || height <= 0) throw Error(who, "image size is empty");
  if (!(ts.opaque_alpha > 0 && ts.opaque_alpha <= 1)) throw Error(who, "opaque_alpha must lie in (0, 1]");
  const Device d = rays.pixels.device();
  const std::size_t P = std::size_t(width) * height, n = rays.count;
  check_buffer(who, rays.pixels, n, d, "ray pixel list");
  check_buffer(who, color, 3 * n, d, "traced colour");
  check_buffer(who, alpha, n, d, "traced alpha");
  check_finite_buffer(who, color, d, "traced colour");
  check_finite_buffer(who, alpha, d, "traced alpha");
  L = Buffer<T>(3 * P, d);
  V = Buffer<T>(P, d);
  if (on_cuda<T>(who, d)) {
    if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL("shading", shading::cuda::traced_to_images(P, rays.pixels.data(), n, color.data(), alpha.data(),
                                                                 ts, L.data(), V.data()));
    return;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (rays.pixels[i] >= P) throw Error(who, "ray pixel index outside the " + std::to_string(width) + "x" +
                                                  std::to_string(height) + " image");
  ops::traced_to_images(Device::CPU, P, rays.pixels.data(), n, color.data(), alpha.data(), ts, L.data(), V.data());
}

template <class T>
void traced_to_images_backward(const ReflectionRaysT<T>& rays, int width, int height, const Buffer<T>& color,
                               const Buffer<T>& alpha, const TracedImageSettings& ts, const Buffer<T>& dL,
                               const Buffer<T>& dV, Buffer<T>& dcolor, Buffer<T>& dalpha) {
  const char* who = "traced images backward";
  if (width <= 0 || height <= 0) throw Error(who, "image size is empty");
  const Device d = rays.pixels.device();
  const std::size_t P = std::size_t(width) * height, n = rays.count;
  check_buffer(who, rays.pixels, n, d, "ray pixel list");
  check_buffer(who, color, 3 * n, d, "traced colour");
  check_buffer(who, alpha, n, d, "traced alpha");
  check_buffer(who, dL, 3 * P, d, "dL/dL_ind");
  if (!dV.empty()) check_buffer(who, dV, P, d, "dL/dV");
  dcolor = Buffer<T>(3 * n, d);
  dalpha = Buffer<T>(n, d);
  const T* dv = dV.empty() ? nullptr : dV.data();
  if (on_cuda<T>(who, d)) {
    if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL("shading", shading::cuda::traced_to_images_backward(P, rays.pixels.data(), n, color.data(),
                                                                          alpha.data(), ts, dL.data(), dv,
                                                                          dcolor.data(), dalpha.data()));
    return;
  }
  ops::traced_to_images_backward(Device::CPU, P, rays.pixels.data(), n, color.data(), alpha.data(), ts, dL.data(),
                                 dv, dcolor.data(), dalpha.data());
}

template <class T>
ShadeOutputsT<T> shade(const Camera& cam, const SurfaceImagesT<T>& s, const Buffer<T>& L, const Buffer<T>& V,
                       const envmap::CubeMipsT<T>& env, const ShadingSettings& st, Device d, bool maps) {
  const char* who = "shading";
  check_settings(who, st);
  check_camera(who, cam, s.width, s.height);
  check_surface(who, s, d);
  check_env(who, env);
  const std::size_t P = s.pixels();
  check_buffer(who, L, 3 * P, d, "L_ind image");
  check_buffer(who, V, P, d, "visibility image");
  check_finite_buffer(who, L, d, "L_ind image");
  check_finite_buffer(who, V, d, "visibility image");
  ShadeOutputsT<T> out;
  out.color = Buffer<T>(3 * P, d);
  if (maps) out.glossy = Buffer<T>(3 * P, d), out.env_radiance = Buffer<T>(3 * P, d);
  T* glossy = maps ? out.glossy.data() : nullptr;
  T* ldir = maps ? out.env_radiance.data() : nullptr;
  if (on_cuda<T>(who, d)) {
    if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL("shading", shading::cuda::shade(cam, s, L.data(), V.data(), env, st, out.color.data(), glossy,
                                                      ldir));
    return out;
  }
  ops::shade(Device::CPU, cam, s, L.data(), V.data(), env, st, out.color.data(), glossy, ldir);
  return out;
}

template <class T>
void shade_backward(const Camera& cam, const SurfaceImagesT<T>& s, const Buffer<T>& L, const Buffer<T>& V,
                    const envmap::CubeMipsT<T>& env, const ShadingSettings& st, const Buffer<T>& dcolor,
                    const SurfaceGradsT<T>& g, Buffer<T>& dL, Buffer<T>& dV, T* env_grad, Device d) {
  const char* who = "shading backward";
  check_settings(who, st);
  check_camera(who, cam, s.width, s.height);
  check_surface(who, s, d);
  check_env(who, env);
  const std::size_t P = s.pixels();
  check_buffer(who, L, 3 * P, d, "L_ind image");
  check_buffer(who, V, P, d, "visibility image");
  check_buffer(who, dcolor, 3 * P, d, "dL/dC");
  check_finite_buffer(who, dcolor, d, "dL/dC");
  dL = Buffer<T>(3 * P, d);
  dV = Buffer<T>(P, d);
  if (on_cuda<T>(who, d)) {
    if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL("shading", shading::cuda::shade_backward(cam, s, L.data(), V.data(), env, st, dcolor.data(), g,
                                                               dL.data(), dV.data(), env_grad));
    return;
  }
  ops::shade_backward(Device::CPU, cam, s, L.data(), V.data(), env, st, dcolor.data(), g, dL.data(), dV.data(),
                      env_grad);
}

#define GORIS_SHADING_INSTANTIATE(T)                                                                              \
  template SurfaceImagesT<T> surface_from_gbuffer(const GBufferT<T>&, const MaterialChannels&);                  \
  template ReflectionRaysT<T> make_reflection_rays(const Camera&, const SurfaceImagesT<T>&, const ShadingSettings&, \
                                                   Device);                                                       \
  template void reflection_rays_backward(const Camera&, const SurfaceImagesT<T>&, const ShadingSettings&,         \
                                         const ReflectionRaysT<T>&, const T*, const T*, const SurfaceGradsT<T>&,  \
                                         Device);                                                                 \
  template void traced_to_images(const ReflectionRaysT<T>&, int, int, const Buffer<T>&, const Buffer<T>&,         \
                                 const TracedImageSettings&, Buffer<T>&, Buffer<T>&);                             \
  template void traced_to_images_backward(const ReflectionRaysT<T>&, int, int, const Buffer<T>&, const Buffer<T>&, \
                                          const TracedImageSettings&, const Buffer<T>&, const Buffer<T>&,          \
                                          Buffer<T>&, Buffer<T>&);                                                \
  template ShadeOutputsT<T> shade(const Camera&, const SurfaceImagesT<T>&, const Buffer<T>&, const Buffer<T>&,    \
                                  const envmap::CubeMipsT<T>&, const ShadingSettings&, Device, bool);             \
  template void shade_backward(const Camera&, const SurfaceImagesT<T>&, const Buffer<T>&, const Buffer<T>&,       \
                               const envmap::CubeMipsT<T>&, const ShadingSettings&, const Buffer<T>&,             \
                               const SurfaceGradsT<T>&, Buffer<T>&, Buffer<T>&, T*, Device);

GORIS_SHADING_INSTANTIATE(float)
GORIS_SHADING_INSTANTIATE(double)

}  // namespace goris
