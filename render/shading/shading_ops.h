#pragma once
// Device-generic drivers of deferred shading, written once on parallel_for: deferred_shading.cpp runs them
// on the CPU (float and double), shading_cuda.cu on CUDA. Inputs are validated by the callers
// (deferred_shading.cpp); every pointer lives on `d`.
#include <cstdint>

#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "render/envmap/cube_map_math.h"
#include "render/envmap/deferred_texel_grads.h"
#include "render/envmap/env_proxy_math.h"
#include "render/shading/shading_math.h"
#include "render/shading/shading_types.h"

namespace goris::shading::ops {
GORIS_BACKEND_NAMESPACE_BEGIN

template <class T>
GORIS_HDI bool is_glossy(const SurfaceImagesT<T>& s, const ShadingSettings& st, std::size_t p) {
  const T a = s.alpha[p];
  if (!(a > T(st.min_alpha)) || !(s.depth[p] > T(0))) return false;
  const T M = st.normalize_materials ? s.region[p] / a : s.region[p];
  return M < T(st.glossy_max_region);
}

// Surface point of pixel p: x = camera centre + (depth / alpha) d_raw (depth is camera z, not ray length).
template <class T>
GORIS_HDI Vec3<T> surface_point(const Camera& cam, const SurfaceImagesT<T>& s, const PixelGeometry<T>& g,
                                std::size_t p) {
  return Vec3<T>(cam.center()) + (s.depth[p] / s.alpha[p]) * g.d_raw;
}

// dL/dx of surface_point -> dL/d(depth), dL/d(alpha) (+=).
template <class T>
GORIS_HDI void surface_point_vjp(const SurfaceImagesT<T>& s, const SurfaceGradsT<T>& g, const PixelGeometry<T>& geo,
                                 std::size_t p, const Vec3<T>& dx) {
  const T a = s.alpha[p];
  const T dz = glm::dot(dx, geo.d_raw);
  if (g.depth) g.depth[p] += dz / a;
  if (g.alpha) g.alpha[p] -= dz * s.depth[p] / (a * a);
}

// Surface point and reflection ray of pixel p.
template <class T>
GORIS_HDI void reflection_ray(const Camera& cam, const SurfaceImagesT<T>& s, const ShadingSettings& st,
                              std::size_t p, Vec3<T>* origin, Vec3<T>* dir) {
  const std::size_t P = s.pixels();
  const PixelGeometry<T> g = pixel_geometry(cam, int(p % s.width), int(p / s.width), plane3(s.normal, P, p));
  *origin = surface_point(cam, s, g, p) + T(st.ray_offset) * g.wr;
  *dir = g.wr;
}

template <class T>
ReflectionRaysT<T> make_rays(Device d, const Camera& cam, const SurfaceImagesT<T>& s, const ShadingSettings& st) {
  const std::size_t P = s.pixels();
  ReflectionRaysT<T> out;
  Buffer<std::uint32_t> flags(P, d), offsets(P, d);
  std::uint32_t* f = flags.data();
  parallel_for(d, P, [=] GORIS_HD(std::size_t p) { f[p] = is_glossy(s, st, p) ? 1u : 0u; });
  exclusive_scan(flags, offsets);
  std::uint32_t last[2] = {0, 0};
  device_copy(&last[0], Device::CPU, offsets.data() + (P - 1), d, sizeof(std::uint32_t));
  device_copy(&last[1], Device::CPU, flags.data() + (P - 1), d, sizeof(std::uint32_t));
  out.count = std::size_t(last[0]) + last[1];
  out.pixels = Buffer<std::uint32_t>(out.count, d);
  out.origins = Buffer<T>(3 * out.count, d);
  out.directions = Buffer<T>(3 * out.count, d);
  std::uint32_t* pix = out.pixels.data();
  const std::uint32_t* off = offsets.data();
  parallel_for(d, P, [=] GORIS_HD(std::size_t p) {
    if (f[p]) pix[off[p]] = std::uint32_t(p);
  });
  T* o = out.origins.data();
  T* w = out.directions.data();
  parallel_for(d, out.count, [=] GORIS_HD(std::size_t i) {
    Vec3<T> org, dir;
    reflection_ray(cam, s, st, pix[i], &org, &dir);
    for (int c = 0; c < 3; ++c) o[3 * i + c] = org[c], w[3 * i + c] = dir[c];
  });
  return out;
}

// d(origin), d(direction) per ray -> dL/d(depth, alpha, normal) of its pixel (+=; one ray per pixel).
template <class T>
void rays_backward(Device d, const Camera& cam, const SurfaceImagesT<T>& s, const ShadingSettings& st,
                   const std::uint32_t* pixels, std::size_t n, const T* dorigins, const T* ddirections,
                   const SurfaceGradsT<T>& g) {
  const std::size_t P = s.pixels();
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
    const std::size_t p = pixels[i];
    const PixelGeometry<T> geo = pixel_geometry(cam, int(p % s.width), int(p / s.width), plane3(s.normal, P, p));
    const Vec3<T> dorg = dorigins ? Vec3<T>(dorigins[3 * i], dorigins[3 * i + 1], dorigins[3 * i + 2]) : Vec3<T>(T(0));
    Vec3<T> dwr = T(st.ray_offset) * dorg;
    if (ddirections) dwr += Vec3<T>(ddirections[3 * i], ddirections[3 * i + 1], ddirections[3 * i + 2]);
    surface_point_vjp(s, g, geo, p, dorg);
    if (g.normal) add_plane3(g.normal, P, p, reflection_vjp_to_camera_normal(geo, dwr));
  });
}

// Per-ray traced colour / alpha -> L_ind [3][H][W] and V [H][W]; untraced pixels get L = 0, V = 1 (the
// environment seen unoccluded, so rough surface pixels keep a gradient towards glossiness).
template <class T>
void traced_to_images(Device d, std::size_t P, const std::uint32_t* pixels, std::size_t n, const T* color,
                      const T* alpha, const TracedImageSettings& ts, T* L, T* V) {
  parallel_for(d, P, [=] GORIS_HD(std::size_t p) {
    L[p] = L[P + p] = L[2 * P + p] = T(0);
    V[p] = T(1);
  });
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
    const std::size_t p = pixels[i];
    const T a = alpha[i];
    const bool opaque = ts.divide_opaque && a >= T(ts.opaque_alpha);
    const T scale = opaque ? T(1) / a : T(1);
    for (int c = 0; c < 3; ++c) L[c * P + p] = color[3 * i + c] * scale;
    V[p] = opaque ? T(0) : T(1) - a;
  });
}

template <class T>
void traced_to_images_backward(Device d, std::size_t P, const std::uint32_t* pixels, std::size_t n,
                               const T* color, const T* alpha, const TracedImageSettings& ts, const T* dL,
                               const T* dV, T* dcolor, T* dalpha) {
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
    const std::size_t p = pixels[i];
    const T a = alpha[i];
    const bool opaque = ts.divide_opaque && a >= T(ts.opaque_alpha);
    const T scale = opaque ? T(1) / a : T(1);
    T da = T(0);
    for (int c = 0; c < 3; ++c) {
      const T g = dL ? dL[c * P + p] : T(0);
      if (dcolor) dcolor[3 * i + c] = g * scale;
      if (opaque) da -= g * color[3 * i + c] * scale * scale;
    }
    if (!opaque && dV) da -= dV[p];
    if (dalpha) dalpha[i] = da;
  });
}

// Everything the combine needs per pixel, and its forward value.
template <class T>
struct CombineState {
  PixelGeometry<T> geo;
  Materials<T> mat;
  T rough;          // roughness handed to the lookup
  envmap::ProxyHit<T> env_hit;  // where the environment is read (env_hit.dir; omega_r at infinity)
  T k;              // Schlick weight (constant)
  Vec3<T> F, Lind, Ldir, G;
  T V;
};

template <class T>
GORIS_HDI CombineState<T> combine_state(const Camera& cam, const SurfaceImagesT<T>& s, const T* L, const T* V,
                                        const envmap::CubeMipsT<T>& env, const ShadingSettings& st, std::size_t p) {
  const std::size_t P = s.pixels();
  CombineState<T> c;
  c.geo = pixel_geometry(cam, int(p % s.width), int(p / s.width), plane3(s.normal, P, p));
  c.mat = read_materials(s.region[p], plane3(s.f0, P, p), s.roughness[p], s.alpha[p], st.normalize_materials);
  c.rough = c.mat.r;
  c.k = schlick_weight(c.geo.cos_r);
  c.F = c.mat.f0 + (Vec3<T>(T(1)) - c.mat.f0) * c.k;
  c.Lind = plane3(L, P, p);
  c.V = V[p];
  const Vec3<T> centre(T(st.env_center[0]), T(st.env_center[1]), T(st.env_center[2]));
  c.env_hit = envmap::proxy_hit(surface_point(cam, s, c.geo, p), c.geo.wr, centre, T(st.env_radius));
  c.Ldir = envmap::cube_lookup(env, c.env_hit.dir, c.rough);
  c.G = c.F * (c.Lind + c.Ldir * c.V);
  return c;
}

// C = D + (1 - M) G on surface pixels (alpha > min_alpha), C = D elsewhere. Optional maps (null: skipped):
// glossy G (before the (1 - M) weight) and the prefiltered environment radiance L_dir'.
template <class T>
void shade(Device d, const Camera& cam, const SurfaceImagesT<T>& s, const T* L, const T* V,
           const envmap::CubeMipsT<T>& env, const ShadingSettings& st, T* color, T* glossy, T* ldir) {
  const std::size_t P = s.pixels();
  parallel_for(d, P, [=] GORIS_HD(std::size_t p) {
    Vec3<T> C = plane3(s.color, P, p), G(T(0)), Ld(T(0));
    if (s.alpha[p] > T(st.min_alpha)) {
      const CombineState<T> c = combine_state(cam, s, L, V, env, st, p);
      C += (T(1) - c.mat.M) * c.G;
      G = c.G;
      Ld = c.Ldir;
    }
    for (int ch = 0; ch < 3; ++ch) {
      color[ch * P + p] = C[ch];
      if (glossy) glossy[ch * P + p] = G[ch];
      if (ldir) ldir[ch * P + p] = Ld[ch];
    }
  });
}

// Backward of shade: surface grads +=, dL / dV written (zero off the surface), env_grad += dL/dtexels
// (in a fixed order on both backends, see deferred_texel_grads.h).
template <class T>
void shade_backward(Device d, const Camera& cam, const SurfaceImagesT<T>& s, const T* L, const T* V,
                    const envmap::CubeMipsT<T>& env, const ShadingSettings& st, const T* dcolor,
                    const SurfaceGradsT<T>& g, T* dL, T* dV, T* env_grad) {
  const std::size_t P = s.pixels();
  envmap::DeferredTexelGrads<T> texels(d, env_grad, P);
  T* const records = texels.records();
  parallel_for(d, P, [=] GORIS_HD(std::size_t p) {
    const Vec3<T> dC = plane3(dcolor, P, p);
    if (g.color) add_plane3(g.color, P, p, dC);
    if (!(s.alpha[p] > T(st.min_alpha))) {
      if (dL) dL[p] = dL[P + p] = dL[2 * P + p] = T(0);
      if (dV) dV[p] = T(0);
      return;
    }
    const CombineState<T> c = combine_state(cam, s, L, V, env, st, p);
    const Vec3<T> dG = (T(1) - c.mat.M) * dC;
    const T dM = -glm::dot(dC, c.G);
    const Vec3<T> dF = dG * (c.Lind + c.Ldir * c.V);
    const Vec3<T> dLind = dG * c.F;
    const Vec3<T> dLdir = dLind * c.V;
    if (dL) dL[p] = dLind.x, dL[P + p] = dLind.y, dL[2 * P + p] = dLind.z;
    if (dV) dV[p] = glm::dot(dLind, c.Ldir);
    const Vec3<T> df0 = dF * (T(1) - c.k);
    Vec3<T> dlook, dwr(T(0)), dx(T(0));
    T drough;
    envmap::cube_lookup_vjp(env, c.env_hit.dir, c.rough, dLdir, &dlook, &drough);
    envmap::DeferredTexelGrads<T>::record(records, p, c.env_hit.dir, c.rough, dLdir);
    envmap::proxy_hit_vjp(c.env_hit, c.geo.wr, T(st.env_radius), dlook, &dwr, &dx);
    if (c.env_hit.hit) surface_point_vjp(s, g, c.geo, p, dx);
    // Through the normalisation by alpha: x_hat = x * scale.
    const T sc = c.mat.scale;
    if (g.region) g.region[p] += dM * sc;
    if (g.f0) add_plane3(g.f0, P, p, df0 * sc);
    if (g.roughness) g.roughness[p] += drough * sc;
    if (g.alpha && st.normalize_materials)
      g.alpha[p] -= (dM * c.mat.M + glm::dot(df0, c.mat.f0) + drough * c.mat.r) * sc;
    if (g.normal) add_plane3(g.normal, P, p, reflection_vjp_to_camera_normal(c.geo, dwr));
  });
  texels.flush(env);
}

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris::shading::ops
