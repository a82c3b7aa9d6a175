#pragma once
// Input validation of the deferred-shading entry points: every problem becomes a goris::Error that names
// the stage and the offending input. Values are scanned for NaN/Inf on the CPU backend only (a device scan
// would cost a transfer per image; the CUDA path trusts the CPU-tested pipeline, as the tracer does).
#include <cmath>
#include <cstddef>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/compute/buffer.h"
#include "core/io/camera.h"
#include "core/util/error.h"
#include "render/envmap/cube_map_math.h"
#include "render/shading/shading_types.h"

namespace goris::shading {

template <class T>
bool all_finite(const T* p, std::size_t n) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n), true,
      [p](const tbb::blocked_range<std::size_t>& r, bool ok) {
        for (std::size_t i = r.begin(); ok && i != r.end(); ++i) ok = std::isfinite(p[i]);
        return ok;
      },
      [](bool a, bool b) { return a && b; });
}

inline void check_settings(const char* who, const ShadingSettings& s) {
  if (!(s.min_alpha >= 0 && s.min_alpha < 1)) throw Error(who, "min_alpha must lie in [0, 1)");
  if (!(s.glossy_max_region > 0) || !std::isfinite(s.glossy_max_region))
    throw Error(who, "glossy_max_region must be positive and finite");
  if (!(s.ray_offset >= 0) || !std::isfinite(s.ray_offset)) throw Error(who, "ray_offset must be >= 0 and finite");
  if (!(s.env_radius >= 0) || !std::isfinite(s.env_radius)) throw Error(who, "env_radius must be >= 0 and finite");
  for (float c : s.env_center)
    if (!std::isfinite(c)) throw Error(who, "env_center must be finite");
}

inline void check_camera(const char* who, const Camera& cam, int width, int height) {
  if (width <= 0 || height <= 0) throw Error(who, "surface images are empty");
  if (cam.width != width || cam.height != height)
    throw Error(who, "camera is " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                         " but the surface images are " + std::to_string(width) + "x" + std::to_string(height));
  if (!(cam.fx > 0) || !(cam.fy > 0)) throw Error(who, "camera focal lengths must be positive");
  if (cam.has_distortion()) throw Error(who, "camera has lens distortion; shading needs undistorted images");
}

// Null planes always; non-finite values on the CPU.
template <class T>
void check_surface(const char* who, const SurfaceImagesT<T>& s, Device d) {
  struct Plane {
    const T* p;
    std::size_t channels;
    const char* name;
  };
  const Plane planes[] = {{s.color, 3, "colour"},  {s.alpha, 1, "alpha"}, {s.depth, 1, "depth"},
                          {s.normal, 3, "normal"}, {s.region, 1, "region weight"}, {s.f0, 3, "F0"},
                          {s.roughness, 1, "roughness"}};
  for (const Plane& pl : planes) {
    if (!pl.p) throw Error(who, std::string("surface ") + pl.name + " image is missing");
    if (d == Device::CPU && !all_finite(pl.p, pl.channels * s.pixels()))
      throw Error(who, std::string("surface ") + pl.name + " image has non-finite values");
  }
}

template <class U>
void check_buffer(const char* who, const Buffer<U>& b, std::size_t expected, Device d, const std::string& name) {
  if (b.size() != expected)
    throw Error(who, name + " has " + std::to_string(b.size()) + " values, expected " + std::to_string(expected));
  if (expected > 0 && b.device() != d) throw Error(who, name + " lives on another device than the stage runs on");
}

template <class T>
void check_finite_buffer(const char* who, const Buffer<T>& b, Device d, const std::string& name) {
  if (d == Device::CPU && !all_finite(b.data(), b.size())) throw Error(who, name + " has non-finite values");
}

template <class T>
void check_env(const char* who, const envmap::CubeMipsT<T>& env) {
  const int R = env.resolution;
  if (!env.texels || R <= 0 || (R & (R - 1)) != 0 || env.levels < 1 || env.levels > envmap::kMaxLevels ||
      (R >> (env.levels - 1)) < 1)
    throw Error(who, "environment map view is empty or inconsistent (call EnvironmentMap::update first)");
}

template <class T>
constexpr bool is_float() {
  return sizeof(T) == sizeof(float);
}

}  // namespace goris::shading
