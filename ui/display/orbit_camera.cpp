#include "ui/display/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace goris::ui {

namespace {
constexpr float kMaxPitch = 1.5533f;  // 89 degrees: the view never lines up with `up` (no flip)
}

void OrbitCamera::set_world(const glm::vec3& up, const glm::vec3& center, float radius) {
  const float len = glm::length(up);
  up_ = len > 1e-6f ? up / len : glm::vec3(0, 0, 1);
  center_ = center;
  radius_ = radius > 1e-6f ? radius : 1.0f;
  target_ = center;
  distance_ = 1.5f * radius_;
}

void OrbitCamera::basis(glm::vec3& e1, glm::vec3& e2) const {
  // Any fixed perpendicular works; pick the world axis least aligned with up for stability.
  const glm::vec3 a = std::abs(up_.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  e1 = glm::normalize(a - up_ * glm::dot(a, up_));
  e2 = glm::cross(up_, e1);
}

glm::vec3 OrbitCamera::offset_direction() const {
  glm::vec3 e1, e2;
  basis(e1, e2);
  return std::cos(pitch_) * (std::cos(yaw_) * e1 + std::sin(yaw_) * e2) + std::sin(pitch_) * up_;
}

glm::vec3 OrbitCamera::eye() const { return target_ + distance_ * offset_direction(); }
glm::vec3 OrbitCamera::forward() const { return -offset_direction(); }

void OrbitCamera::orbit(float d_yaw, float d_pitch) {
  yaw_ += d_yaw;
  pitch_ = std::clamp(pitch_ + d_pitch, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::look(float d_yaw, float d_pitch) {
  const glm::vec3 e = eye();
  // Yaw grows counter-clockwise around up (a turn to the left), so looking right lowers it; looking up
  // lowers the eye-from-target direction, i.e. the pitch.
  yaw_ -= d_yaw;
  pitch_ = std::clamp(pitch_ - d_pitch, -kMaxPitch, kMaxPitch);
  target_ = e - distance_ * offset_direction();
}

void OrbitCamera::pan(float dx, float dy) {
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, up_));
  const glm::vec3 down = glm::cross(f, right);
  const float view_height = 2.0f * distance_ * std::tan(0.5f * fov_y_);
  target_ += (dx * right + dy * down) * view_height;
}

void OrbitCamera::zoom(float steps) {
  distance_ = std::clamp(distance_ * std::pow(0.9f, steps), 1e-3f * radius_, 100.0f * radius_);
}

void OrbitCamera::fly(float fwd, float right_amount, float up_amount) {
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, up_));
  target_ += fwd * f + right_amount * right + up_amount * up_;
}

void OrbitCamera::set_fov_y(float radians) { fov_y_ = std::clamp(radians, 0.05f, 3.0f); }

void OrbitCamera::snap_to(const Camera& cam) {
  const glm::vec3 e = cam.center();
  const glm::vec3 f = glm::normalize(cam.forward());
  distance_ = std::max(glm::dot(center_ - e, f), 0.1f * radius_);
  target_ = e + distance_ * f;
  const glm::vec3 back = -f;
  pitch_ = std::asin(std::clamp(glm::dot(back, up_), -1.0f, 1.0f));
  pitch_ = std::clamp(pitch_, -kMaxPitch, kMaxPitch);
  glm::vec3 e1, e2;
  basis(e1, e2);
  yaw_ = std::atan2(glm::dot(back, e2), glm::dot(back, e1));
  if (cam.height > 0 && cam.fy > 0) set_fov_y(2.0f * std::atan(0.5f * float(cam.height) / cam.fy));
}

Camera OrbitCamera::camera(int width, int height) const {
  Camera c;
  c.width = width;
  c.height = height;
  c.fy = 0.5f * float(height) / std::tan(0.5f * fov_y_);
  c.fx = c.fy;
  c.cx = 0.5f * float(width);
  c.cy = 0.5f * float(height);
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, up_));
  const glm::vec3 down = glm::cross(f, right);
  // Rows of R are the camera axes in world coordinates (GLM is column-major: R[col][row]).
  glm::mat3 R;
  for (int k = 0; k < 3; ++k) {
    R[k][0] = right[k];
    R[k][1] = down[k];
    R[k][2] = f[k];
  }
  c.R = R;
  c.t = -(R * eye());
  return c;
}

}  // namespace goris::ui
