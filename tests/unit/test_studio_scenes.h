#pragma once
// What the editor's unit tests look at: a small camera in front of the origin, and Gaussians set up one by
// one.
#include <algorithm>
#include <cmath>

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

}  // namespace goris::test
