#pragma once
// Types of the deferred shading stage (docs/design/maths.md, Shading), templated on the scalar type like
// the rasterizer's (float in production, double in the gradient tests). Images are planar [C][H][W] as the
// G-buffer stores them; every pointer lives on the device the stage runs on.
#include <cstddef>
#include <cstdint>

#include "core/compute/buffer.h"
#include "core/compute/hd.h"

namespace goris {

// The rasterized surface a pixel sees. `color`, `alpha`, `depth`, `normal` are the G-buffer's channels
// (depth = sum w z and normal = sum w n in camera space, neither normalised); `region` (M), `f0` (3
// planes) and `roughness` are extra channels (sum w e). Build one from a G-buffer with
// surface_from_gbuffer (deferred_shading.h), which checks the sizes.
template <class T>
struct SurfaceImagesT {
  int width = 0, height = 0;
  const T* color = nullptr;      // D [3][H][W]
  const T* alpha = nullptr;      // [H][W]
  const T* depth = nullptr;      // [H][W]
  const T* normal = nullptr;     // [3][H][W]
  const T* region = nullptr;     // M [H][W]
  const T* f0 = nullptr;         // [3][H][W]
  const T* roughness = nullptr;  // [H][W]
  GORIS_HD std::size_t pixels() const { return std::size_t(width) * std::size_t(height); }
};

// dL/d(surface images), same layouts; accumulated (+=) because several stages (shading, reflection rays,
// losses) feed the same G-buffer channels. Null planes are skipped.
template <class T>
struct SurfaceGradsT {
  T* color = nullptr;
  T* alpha = nullptr;
  T* depth = nullptr;
  T* normal = nullptr;
  T* region = nullptr;
  T* f0 = nullptr;
  T* roughness = nullptr;
};

struct ShadingSettings {
  // A pixel is a surface when its alpha exceeds this; elsewhere there is no glossy term and no ray.
  float min_alpha = 0.5f;
  // Surface pixels with region weight M >= this are rough (M ~ 1): they are not traced.
  float glossy_max_region = 0.99f;
  // Ray origins start at x + ray_offset * omega_r (world units); see default_ray_offset(). A grazing ray
  // barely leaves the surface's own Gaussians yet skips whatever stands within ray_offset of the point (an
  // object's foot and its reflection); an offset along the normal instead measured no better.
  float ray_offset = 0.1f;
  // Divide M, F0 and roughness by alpha (per-surface values instead of coverage-weighted sums), the way
  // depth is divided by alpha and the normal normalised. Off: use the rasterized sums as they are.
  bool normalize_materials = true;
  // The environment map's sphere (envmap/env_proxy_math.h): radius 0 = at infinity (the paper).
  float env_center[3] = {0.0f, 0.0f, 0.0f};
  float env_radius = 0.0f;

  // The authors start rays 0.1 world units off the surface on scenes whose 3DGS "extent" (1.1 x the camera
  // spread radius) is about 4-5; scaled to other scenes that is 0.02 x extent.
  static float default_ray_offset(float scene_extent) { return 0.02f * scene_extent; }
};

// One reflection ray per glossy pixel, compacted: ray i starts at origins[i] in direction directions[i]
// (unit omega_r) and belongs to pixel pixels[i] (y * W + x), in increasing pixel order.
template <class T>
struct ReflectionRaysT {
  Buffer<std::uint32_t> pixels;  // [n]
  Buffer<T> origins;             // [n][3]
  Buffer<T> directions;          // [n][3]
  std::size_t count = 0;
};

// Options for turning per-ray traced results into the L_ind / V images the shading reads.
struct TracedImageSettings {
  // The authors divide the traced colour by its alpha where the ray is nearly opaque (and take V = 0
  // there), which undoes the last fraction of transmittance the tracer leaves. Our tracer stops *before*
  // the hit that would bring T under 1e-4 and caps a hit's alpha at 0.99, so an opaque ray ends anywhere in
  // alpha [0.99, 0.9999]: hence the 0.99 threshold (the authors' tracer stops after it, at 1 - 1e-4).
  bool divide_opaque = true;
  float opaque_alpha = 0.99f;
};

using SurfaceImages = SurfaceImagesT<float>;
using SurfaceGrads = SurfaceGradsT<float>;
using ReflectionRays = ReflectionRaysT<float>;

}  // namespace goris
