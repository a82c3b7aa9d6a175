#pragma once
// What the editor's unit tests look at: a small camera in front of the origin, Gaussians set up one by
// one, and two separate blobs of them.
#include <algorithm>
#include <cmath>
#include <random>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"

namespace goris::test {

// 48 x 40 pixels at (0, 0, -4) looking down +z (identity rotation), focal length 50.
inline Camera studio_front_camera() {
  Camera c;
  c.width = 48;
  c.height = 40;
  c.fx = c.fy = 50;
  c.cx = 24;
  c.cy = 20;
  c.t = glm::vec3(0, 0, 4);
  return c;
}

// Gaussian i of `m`: centre, axis scales, identity rotation, opacity logit 4 (~0.98), SH DC `dc` (higher
// coefficients zero); the extras are left to the caller.
inline void set_studio_gaussian(GaussianModel& m, int i, glm::vec3 position, glm::vec3 scale, glm::vec3 dc) {
  for (int a = 0; a < 3; ++a) {
    m.values(Param::Position)[i * 3 + a] = position[a];
    m.values(Param::LogScale)[i * 3 + a] = std::log(scale[a]);
  }
  float* q = m.values(Param::Rotation) + i * 4;
  q[0] = 1;
  q[1] = q[2] = q[3] = 0;
  m.values(Param::OpacityLogit)[i] = 4.0f;
  float* sh = m.values(Param::Sh) + i * 48;
  std::fill(sh, sh + 48, 0.0f);
  for (int c = 0; c < 3; ++c) sh[c] = dc[c];
}

// Two blobs of `per_blob` Gaussians each: blob 0 (red, label logit +4) around x = -1, blob 1 (blue, label
// logit -4) around x = +1, both about z = 0. Seen from studio_front_camera(), blob 0 projects to
// u ~ 11.5 and blob 1 to u ~ 36.5 (v ~ 20).
inline GaussianModel studio_two_blobs(int per_blob) {
  std::mt19937 rng(5);
  std::normal_distribution<float> g(0.0f, 0.12f);
  GaussianModel m(Device::CPU);
  m.allocate(std::size_t(2 * per_blob));
  for (int i = 0; i < 2 * per_blob; ++i) {
    const int blob = i / per_blob;
    const glm::vec3 position((blob == 0 ? -1.0f : 1.0f) + g(rng), g(rng), g(rng));
    const glm::vec3 dc = blob == 0 ? glm::vec3(1.5f, 0.0f, -1.5f) : glm::vec3(-1.5f, 0.0f, 1.5f);  // red or blue
    set_studio_gaussian(m, i, position, glm::vec3(0.06f), dc);
    for (int k = 0; k < extra::kCount; ++k)
      m.values(Param::ExtraLogit)[i * extra::kCount + k] = k == extra::kLabel ? (blob == 0 ? 4.0f : -4.0f) : 0.0f;
  }
  return m;
}

}  // namespace goris::test
