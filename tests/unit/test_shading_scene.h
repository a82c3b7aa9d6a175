#pragma once
// A small random G-buffer for the shading tests: a rotated, translated camera, surfaces facing it, materials
// away from every clamp and threshold (so finite differences never cross a kink), and a random
// environment chain. Planes are std::vectors so tests can perturb single values.
#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/compute/buffer.h"
#include "core/io/camera.h"
#include "render/envmap/cube_map_math.h"
#include "render/shading/shading_types.h"

namespace goris::test {

struct ShadingScene {
  static constexpr int kEnvRes = 8, kEnvLevels = 4;
  int W = 6, H = 5;
  Camera cam;
  std::vector<double> color, alpha, depth, normal, region, f0, rough, L, V, chain;

  std::size_t P() const { return std::size_t(W) * H; }
  SurfaceImagesT<double> view() const {
    SurfaceImagesT<double> s;
    s.width = W, s.height = H;
    s.color = color.data(), s.alpha = alpha.data(), s.depth = depth.data(), s.normal = normal.data();
    s.region = region.data(), s.f0 = f0.data(), s.roughness = rough.data();
    return s;
  }
  envmap::CubeMipsT<double> env() const { return {chain.data(), kEnvRes, kEnvLevels}; }

  // mirror_f0: F0 = 1 on every pixel, so Schlick's weight (held constant by the backward pass, as the
  // authors do) drops out and the normal's gradient is exact. rough_pixels: pixels with M ~ 1 or no surface.
  static ShadingScene make(unsigned seed, bool mirror_f0, bool rough_pixels = false) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    auto U = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
    ShadingScene s;
    const glm::quat q = glm::normalize(glm::quat(float(U(-1, 1)), float(U(-1, 1)), float(U(-1, 1)), float(U(-1, 1))));
    s.cam.width = s.W, s.cam.height = s.H;
    s.cam.fx = 7.0f, s.cam.fy = 6.5f, s.cam.cx = 3.1f, s.cam.cy = 2.4f;
    s.cam.R = glm::mat3_cast(q);
    s.cam.t = glm::vec3(float(U(-1, 1)), float(U(-1, 1)), float(U(-1, 1)));
    const std::size_t P = s.P();
    s.color.resize(3 * P), s.normal.resize(3 * P), s.f0.resize(3 * P), s.L.resize(3 * P);
    s.alpha.resize(P), s.depth.resize(P), s.region.resize(P), s.rough.resize(P), s.V.resize(P);
    for (std::size_t p = 0; p < P; ++p) {
      const double a = U(0.6, 1.0);
      s.alpha[p] = a;
      s.depth[p] = a * U(1.0, 3.0);
      s.region[p] = a * U(0.0, 0.9);
      s.rough[p] = a * U(0.4, 0.95);  // level in (0.3, 2.9) of the 8-texel chain: no clamp
      // A unit normal tilted from the reversed view ray, scaled like a sum of weights.
      const glm::dvec3 dcam((p % s.W + 0.5 - s.cam.cx) / s.cam.fx, (p / s.W + 0.5 - s.cam.cy) / s.cam.fy, 1.0);
      const glm::dvec3 n = glm::normalize(-glm::normalize(dcam) + glm::dvec3(U(-.4, .4), U(-.4, .4), U(-.4, .4)));
      const double nscale = a * U(0.8, 1.0);
      for (int c = 0; c < 3; ++c) {
        s.color[c * P + p] = U(0, 1);
        s.normal[c * P + p] = n[c] * nscale;
        s.f0[c * P + p] = mirror_f0 ? a : a * U(0.05, 0.9);
        s.L[c * P + p] = U(0, 1);
      }
      s.V[p] = U(0.05, 0.95);
    }
    if (rough_pixels) {
      s.region[1] = s.alpha[1] * 0.995;  // M ~ 1: rough
      s.region[7] = s.alpha[7];          // M = 1
      s.alpha[10] = 0.3;                 // no surface
      s.depth[10] = 0.3 * 2.0;
      s.region[10] = 0.0;
    }
    s.chain.resize(envmap::chain_size(kEnvRes, kEnvLevels));
    for (double& v : s.chain) v = U(0.1, 2.0);
    return s;
  }
};

inline std::vector<double> random_weights(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> w(n);
  for (double& x : w) x = u(rng);
  return w;
}

inline double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace goris::test
