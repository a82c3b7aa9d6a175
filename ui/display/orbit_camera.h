#pragma once
// The viewport camera: orbits a target (left drag), pans (right/middle drag), zooms (wheel) and flies
// (WASD/QE move eye and target together; in fly mode dragging turns the view around the eye). It turns
// into the engine's Camera (core/io/camera.h: world-to-camera, OpenCV axes) for any image size, and can be
// placed exactly where a data set camera is (snap).
#include <glm/glm.hpp>

#include "core/io/camera.h"

namespace goris::ui {

class OrbitCamera {
 public:
  // World "up" (data sets differ: NeRF-synthetic is +z, COLMAP usually -y) and the scene's size, which
  // scales panning, flying and the nearest zoom.
  void set_world(const glm::vec3& up, const glm::vec3& center, float radius);

  // Orbit around the target by yaw/pitch radians (pitch kept inside +-89 degrees).
  void orbit(float d_yaw, float d_pitch);
  // Turn the view direction around the eye (fly look): +d_yaw turns right, +d_pitch looks up; the eye
  // stays, the target moves.
  void look(float d_yaw, float d_pitch);
  // Move the target (and the eye with it) by fractions of the view's height at the target's distance:
  // +dx to the right of the screen, +dy down the screen.
  void pan(float dx, float dy);
  // Multiplies the distance to the target by 0.9^steps (positive steps move closer).
  void zoom(float steps);
  // Fly: moves eye and target along the view (forward), screen right and world up, in world units.
  void fly(float forward, float right, float up);

  // Places the eye and view direction of `cam` exactly; the target lies along the view at the distance
  // where the scene centre is (at least a tenth of the scene radius); the vertical field of view follows
  // the camera's focal length.
  void snap_to(const Camera& cam);

  // The pinhole camera for a width x height image: vertical field of view fov_y, square pixels, centred.
  Camera camera(int width, int height) const;

  glm::vec3 eye() const;
  glm::vec3 forward() const;  // unit, from the eye towards the target
  const glm::vec3& target() const { return target_; }
  float distance() const { return distance_; }
  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  float fov_y() const { return fov_y_; }
  const glm::vec3& up() const { return up_; }
  float scene_radius() const { return radius_; }
  void set_fov_y(float radians);

 private:
  glm::vec3 offset_direction() const;              // unit, from the target towards the eye
  void basis(glm::vec3& e1, glm::vec3& e2) const;  // two unit vectors perpendicular to up_ and each other

  glm::vec3 up_{0, 0, 1};
  glm::vec3 center_{0.0f};
  float radius_ = 1.0f;
  glm::vec3 target_{0.0f};
  float distance_ = 3.0f;
  float yaw_ = 0.0f, pitch_ = 0.4f;
  float fov_y_ = 0.69f;
};

}  // namespace goris::ui
