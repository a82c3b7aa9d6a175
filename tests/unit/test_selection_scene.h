#pragma once
// Hand-built Gaussian scenes for the selection tests: isotropic Gaussians with a chosen centre, size,
// opacity, view-independent colour and label, written into a GaussianModel before activation.
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"

namespace goris::test {

struct TestGaussian {
  glm::vec3 pos{0.0f};
  float scale = 0.05f;    // 1-sigma radius
  float opacity = 0.9f;
  glm::vec3 color{0.5f};  // SH DC colour
  float label = 0.05f;    // activated
};

inline float logit_of(float p) { return std::log(p / (1.0f - p)); }

inline GaussianModel make_model(const std::vector<TestGaussian>& gs) {
  constexpr float kC0 = 0.28209479177387814f;
  GaussianModel m(Device::CPU);
  m.allocate(gs.size());
  m.sh_degree = 0;
  float* pos = m.values(Param::Position);
  float* ls = m.values(Param::LogScale);
  float* rot = m.values(Param::Rotation);
  float* op = m.values(Param::OpacityLogit);
  float* sh = m.values(Param::Sh);
  float* ex = m.values(Param::ExtraLogit);
  for (std::size_t i = 0; i < gs.size(); ++i) {
    const TestGaussian& g = gs[i];
    for (int k = 0; k < 3; ++k) {
      pos[3 * i + k] = g.pos[k];
      ls[3 * i + k] = std::log(g.scale);
    }
    rot[4 * i] = 1.0f;
    rot[4 * i + 1] = rot[4 * i + 2] = rot[4 * i + 3] = 0.0f;
    op[i] = logit_of(g.opacity);
    for (int k = 0; k < 48; ++k) sh[48 * i + k] = 0.0f;
    for (int c = 0; c < 3; ++c) sh[48 * i + c] = (g.color[c] - 0.5f) / kC0;
    for (int e = 0; e < extra::kCount; ++e) ex[extra::kCount * i + e] = 0.0f;
    ex[extra::kCount * i + extra::kLabel] = logit_of(g.label);
  }
  return m;
}

// A pinhole camera at `eye` looking at `target` (world z up), OpenCV axes.
inline Camera look_at(glm::vec3 eye, glm::vec3 target, int w = 128, int h = 128, float f = 300.0f) {
  Camera c;
  c.width = w;
  c.height = h;
  c.fx = c.fy = f;
  c.cx = 0.5f * float(w);
  c.cy = 0.5f * float(h);
  const glm::vec3 fwd = glm::normalize(target - eye);
  glm::vec3 up(0.0f, 0.0f, 1.0f);
  if (std::abs(glm::dot(fwd, up)) > 0.99f) up = glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 right = glm::normalize(glm::cross(fwd, up));
  const glm::vec3 down = glm::cross(fwd, right);
  c.R = glm::transpose(glm::mat3(right, down, fwd));  // rows: the camera axes in world coordinates
  c.t = -(c.R * eye);
  return c;
}

// n x n x m grid of Gaussians with the given spacing, centred at `center`.
inline std::vector<TestGaussian> grid(glm::vec3 center, int nx, int ny, int nz, float spacing, TestGaussian proto) {
  std::vector<TestGaussian> out;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        TestGaussian g = proto;
        g.pos = center + spacing * glm::vec3(float(x) - 0.5f * float(nx - 1), float(y) - 0.5f * float(ny - 1),
                                             float(z) - 0.5f * float(nz - 1));
        out.push_back(g);
      }
  return out;
}

}  // namespace goris::test
