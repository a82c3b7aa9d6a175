#pragma once
// Small building blocks shared by the unit tests: cameras looking at a point, and the central
// finite-difference gradient check every differentiable operation is tested with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"

namespace goris::test {

// A size x size pinhole camera at `eye` looking at `target` (OpenCV axes: x right, y down, z forward;
// the image's up is world +Z as far as the view direction allows).
inline Camera look_at(glm::vec3 eye, glm::vec3 target, int size, float fov_deg) {
  Camera c;
  c.width = c.height = size;
  c.fx = c.fy = 0.5f * size / std::tan(glm::radians(fov_deg) * 0.5f);
  c.cx = c.cy = 0.5f * size;
  const glm::vec3 z = glm::normalize(target - eye);
  const glm::vec3 x = glm::normalize(glm::cross(z, glm::vec3(0, 0, 1)));
  const glm::vec3 y = glm::cross(z, x);
  glm::mat3 R;  // rows x, y, z (world -> camera)
  for (int k = 0; k < 3; ++k) {
    R[k][0] = x[k];
    R[k][1] = y[k];
    R[k][2] = z[k];
  }
  c.R = R;
  c.t = -(R * eye);
  return c;
}

// Checks `grad` against central differences of f at every element of x (tolerance relative to
// 1 + |fd|), and that the check saw a non-zero gradient somewhere.
inline void expect_gradient(const std::function<double(const std::vector<double>&)>& f, std::vector<double> x,
                            const std::vector<double>& grad, double h = 1e-6, double tol = 1e-6) {
  ASSERT_EQ(x.size(), grad.size());
  double max_g = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double x0 = x[i];
    x[i] = x0 + h;
    const double fp = f(x);
    x[i] = x0 - h;
    const double fm = f(x);
    x[i] = x0;
    const double fd = (fp - fm) / (2 * h);
    max_g = std::max(max_g, std::abs(fd));
    ASSERT_NEAR(grad[i], fd, tol * (1.0 + std::abs(fd))) << "element " << i;
  }
  EXPECT_GT(max_g, 0.0) << "the gradient check saw only zeros";
}

}  // namespace goris::test
