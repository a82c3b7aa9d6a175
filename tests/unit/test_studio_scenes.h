#pragma once
// What the editor's unit tests look at: a small camera in front of the origin.
#include "core/io/camera.h"

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

}  // namespace goris::test
