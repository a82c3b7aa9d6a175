#pragma once
// Small random Gaussian scenes and cameras for the rasterizer tests (any scalar type).
#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "render/raster/raster_types.h"

namespace goris::test {

template <class T>
struct RasterScene {
  int count = 0, sh_degree = 0, n_extras = 0;
  std::vector<T> positions, log_scales, rotations, opacity_logits, sh, extras, filter3d;
  bool use_filter3d = false;

  GaussiansT<T> view() const {
    GaussiansT<T> g;
    g.count = count;
    g.positions = positions.data();
    g.log_scales = log_scales.data();
    g.rotations = rotations.data();
    g.opacity_logits = opacity_logits.data();
    g.sh = sh.data();
    g.sh_degree = sh_degree;
    g.extras = extras.data();
    g.n_extras = n_extras;
    g.filter3d_var = use_filter3d ? filter3d.data() : nullptr;
    return g;
  }
};

// A camera at distance `dist` from the origin looking at a point near it, with a random up vector.
inline Camera random_camera(std::mt19937& rng, int w, int h, float focal, float dist) {
  std::normal_distribution<float> n01(0.f, 1.f);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  glm::vec3 eye(n01(rng), n01(rng), n01(rng));
  eye = glm::normalize(eye) * dist;
  const glm::vec3 target(0.1f * u(rng), 0.1f * u(rng), 0.1f * u(rng));
  const glm::vec3 fwd = glm::normalize(target - eye);
  glm::vec3 up(n01(rng), n01(rng), n01(rng));
  const glm::vec3 right = glm::normalize(glm::cross(fwd, up));
  const glm::vec3 down = glm::cross(fwd, right);
  Camera c;
  c.width = w;
  c.height = h;
  c.fx = focal * (1.f + 0.1f * u(rng));
  c.fy = focal * (1.f + 0.1f * u(rng));
  c.cx = 0.5f * w + u(rng);
  c.cy = 0.5f * h + u(rng);
  glm::mat3 R;  // rows: right, down, forward (OpenCV axes); glm is column-major
  for (int k = 0; k < 3; ++k) {
    R[k][0] = right[k];
    R[k][1] = down[k];
    R[k][2] = fwd[k];
  }
  c.R = R;
  c.t = -(R * eye);
  return c;
}

struct SceneSpec {
  int count = 5, sh_degree = 3, n_extras = 2;
  float spread = 0.8f;                  // positions uniform in [-spread, spread]^3
  float scale_lo = 0.12f, scale_hi = 0.35f;
  float logit_lo = -1.0f, logit_hi = 1.0f;
  bool filter3d = false;
};

template <class T>
RasterScene<T> random_scene(std::mt19937& rng, const SceneSpec& spec) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  RasterScene<T> s;
  s.count = spec.count;
  s.sh_degree = spec.sh_degree;
  s.n_extras = spec.n_extras;
  s.use_filter3d = spec.filter3d;
  for (int i = 0; i < spec.count; ++i) {
    for (int k = 0; k < 3; ++k) s.positions.push_back(T(spec.spread * u(rng)));
    for (int k = 0; k < 3; ++k)
      s.log_scales.push_back(T(std::log(spec.scale_lo + (spec.scale_hi - spec.scale_lo) * u01(rng))));
    for (int k = 0; k < 4; ++k) s.rotations.push_back(T(n01(rng)));
    s.opacity_logits.push_back(T(spec.logit_lo + (spec.logit_hi - spec.logit_lo) * u01(rng)));
    for (int k = 0; k < 48; ++k) s.sh.push_back(T(k < 3 ? 0.4 * n01(rng) : 0.15 * n01(rng)));
    for (int e = 0; e < spec.n_extras; ++e) s.extras.push_back(T(u01(rng)));
    s.filter3d.push_back(T(0.002 + 0.01 * u01(rng)));
  }
  if (s.extras.empty()) s.extras.push_back(T(0));  // keep the pointer valid
  return s;
}

}  // namespace goris::test
