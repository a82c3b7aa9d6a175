#pragma once
// Camera paths for exports (`goris export --renders`, distillation): an orbit around the scene and new
// viewpoints between a set of training cameras. Pure camera maths on the engine's convention
// (core/io/camera.h: world-to-camera, OpenCV axes x right, y down, z forward).
//
// The orbit rule (what `--path orbit` renders):
//   up      the normalised mean of the cameras' up directions (-y of their OpenCV axes); +z when they cancel;
//   centre  the point nearest (least squares) to every optical axis: where the cameras look;
//   circle  around the line through the centre along up, at the cameras' mean height above the centre and
//           their mean horizontal distance from that line;
//   frames  N eyes evenly spaced by 360/N degrees, the first in the direction of the first camera, turning
//           counter-clockwise seen from above (right-handed about up), each looking at the centre with the
//           image's up along the world up; size and focal lengths of the first camera.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"

namespace goris {

// The normalised mean of the cameras' up directions; +z when there are none or they cancel out.
glm::vec3 cameras_up(const std::vector<Camera>& cameras);

// The point nearest (least squares) to every camera's optical axis. Throws goris::Error without cameras.
glm::vec3 cameras_focus(const std::vector<Camera>& cameras);

struct OrbitPath {
  glm::vec3 center{0.0f};        // looked at
  glm::vec3 up{0, 0, 1};         // unit; the circle's axis
  glm::vec3 start{1, 0, 0};      // unit, perpendicular to up: direction of frame 0 from the axis
  float radius = 1.0f;           // distance of the eyes from the axis
  float height = 0.0f;           // eyes' offset along up from the centre
  Camera intrinsics;             // size and focal lengths of every frame
};

// The orbit of the rule above. Throws goris::Error when there are no cameras or they all sit on the axis
// (no circle to follow).
OrbitPath orbit_from_cameras(const std::vector<Camera>& cameras);

// The eye of frame k of n (angle 2 pi k / n).
glm::vec3 orbit_eye(const OrbitPath& path, int k, int n);

// n cameras along the orbit (n >= 1, else goris::Error).
std::vector<Camera> orbit_cameras(const OrbitPath& path, int n);

// A camera with the size and focal lengths (principal point too) of `intrinsics` at `eye`, looking at
// `target`, the image's up as close to `up` as the view allows (any perpendicular when they are parallel).
Camera look_at_camera(const Camera& intrinsics, const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up);

// `count` new cameras between training cameras, for sampling view-dependent appearance densely: camera j
// starts from camera j mod n, picks one of its 3 nearest cameras (by centre) at random and sits at a random
// fraction t in [0.25, 0.75] of the way to it, centre interpolated linearly and orientation spherically
// (slerp), intrinsics of the first. Deterministic for a seed. Fewer than two cameras: none.
std::vector<Camera> interpolated_cameras(const std::vector<Camera>& cameras, int count, std::uint64_t seed);

// k indices spread evenly over 0..n-1 (floor(i n / k)); all of them when k <= 0 or k >= n.
std::vector<size_t> evenly_spaced(size_t n, int k);

}  // namespace goris
