#pragma once
// A hand-built scene for the removal's tests: a flat table of Gaussians (z = 0) with a box on it (the
// target), seen from straight above and from eight oblique cameras around it.
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"

namespace goris::test {

constexpr float kSh0 = 0.28209479f;
constexpr float kHalf = 0.2f;  // the box's half width in x and y

struct SceneBuilder {
  std::vector<float> pos, log_scale, rot, opacity, sh;
  std::vector<std::uint8_t> target;
  void add(glm::vec3 p, glm::vec3 scale, float grey, bool is_target) {
    pos.insert(pos.end(), {p.x, p.y, p.z});
    log_scale.insert(log_scale.end(), {std::log(scale.x), std::log(scale.y), std::log(scale.z)});
    rot.insert(rot.end(), {1, 0, 0, 0});
    opacity.push_back(5.0f);
    for (int k = 0; k < kMaxShCoeffs * 3; ++k) sh.push_back(k < 3 ? (grey - 0.5f) / kSh0 : 0.0f);
    target.push_back(is_target ? 1 : 0);
  }
  GaussianModel model() const {
    GaussianModel m(Device::CPU);
    const std::size_t n = target.size();
    m.allocate(n);
    m.tensor(Param::Position).value.upload(pos.data(), pos.size());
    m.tensor(Param::LogScale).value.upload(log_scale.data(), log_scale.size());
    m.tensor(Param::Rotation).value.upload(rot.data(), rot.size());
    m.tensor(Param::OpacityLogit).value.upload(opacity.data(), opacity.size());
    m.tensor(Param::Sh).value.upload(sh.data(), sh.size());
    std::vector<float> extras(n * extra::kCount, 0.0f);
    m.tensor(Param::ExtraLogit).value.upload(extras.data(), extras.size());
    return m;
  }
};

// Table: flat Gaussians on z = 0 over [-2.4, 2.4]^2, large enough to be behind the box in every view
// (optionally with a hole under the box). Box: a filled block over |x|, |y| < 0.2 and z in [z0, z1].
inline SceneBuilder table_and_box(float z0, float z1, bool hole_in_table = false) {
  SceneBuilder s;
  for (int i = 0; i <= 96; ++i)
    for (int j = 0; j <= 96; ++j) {
      const float x = -2.4f + 0.05f * i, y = -2.4f + 0.05f * j;
      if (hole_in_table && std::fabs(x) < kHalf + 0.05f && std::fabs(y) < kHalf + 0.05f) continue;
      s.add({x, y, 0.0f}, {0.035f, 0.035f, 0.004f}, 0.6f, false);
    }
  for (float x = -kHalf + 0.025f; x < kHalf; x += 0.05f)
    for (float y = -kHalf + 0.025f; y < kHalf; y += 0.05f)
      for (float z = z0 + 0.025f; z < z1; z += 0.05f) s.add({x, y, z}, glm::vec3(0.03f), 0.2f, true);
  return s;
}

inline Camera look_at_up(glm::vec3 eye, glm::vec3 at, glm::vec3 up, float focal, int size = 64) {
  const glm::vec3 fwd = glm::normalize(at - eye);
  const glm::vec3 right = glm::normalize(glm::cross(fwd, up));
  const glm::vec3 down = glm::cross(fwd, right);
  Camera c;
  c.width = c.height = size;
  c.fx = c.fy = focal;
  c.cx = c.cy = 0.5f * size;
  for (int k = 0; k < 3; ++k) {  // rows of R: right, down, forward (glm is column-major)
    c.R[k][0] = right[k];
    c.R[k][1] = down[k];
    c.R[k][2] = fwd[k];
  }
  c.t = -(c.R * eye);
  return c;
}

// View 0 straight down from 2.5 above the table (the table's [-0.6, 0.6]^2 fills it); views 1..8 at 45
// degrees elevation, 3 away, every 45 degrees of azimuth.
inline std::vector<Camera> table_cameras() {
  std::vector<Camera> cams = {look_at_up({0, 0, 2.5f}, {0, 0, 0}, {0, 1, 0}, 32.0f / 0.24f)};
  for (int k = 0; k < 8; ++k) {
    const float a = float(k) * 3.14159265f / 4.0f, r = 3.0f * std::cos(3.14159265f / 4.0f);
    cams.push_back(look_at_up({r * std::cos(a), r * std::sin(a), 3.0f * std::sin(3.14159265f / 4.0f)}, {0, 0, 0.3f},
                           {0, 0, 1}, 90.0f));
  }
  return cams;
}

}  // namespace goris::test
