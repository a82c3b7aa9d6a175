#pragma once
// One camera convention for the whole engine (loaders convert to it, renderers consume it):
//  - pose: world-to-camera, x_cam = R * x_world + t, OpenCV axes (x right, y down, z forward);
//  - pinhole intrinsics in pixels: u = fx * x/z + cx, v = fy * y/z + cy, where pixel (i, j) covers
//    [i, i+1) x [j, j+1) and its centre is (i + 0.5, j + 0.5);
//  - optional OpenCV-model distortion (k1, k2, k3 radial, p1, p2 tangential) applied to normalised
//    coordinates before the intrinsics; renderers assume undistorted images (Camera::has_distortion()).
#include <glm/glm.hpp>

#include "core/compute/hd.h"

namespace goris {

struct Distortion {
  float k1 = 0, k2 = 0, k3 = 0, p1 = 0, p2 = 0;
  GORIS_HD bool any() const { return k1 != 0 || k2 != 0 || k3 != 0 || p1 != 0 || p2 != 0; }
};

struct Camera {
  int width = 0, height = 0;
  float fx = 0, fy = 0, cx = 0, cy = 0;
  glm::mat3 R{1.0f};  // world -> camera rotation
  glm::vec3 t{0.0f};  // world -> camera translation
  Distortion dist;

  GORIS_HD glm::vec3 to_camera(const glm::vec3& x_world) const { return R * x_world + t; }
  // Camera centre in world coordinates: -R^T t.
  GORIS_HD glm::vec3 center() const { return -(glm::transpose(R) * t); }
  // Unit viewing direction of the optical axis in world coordinates.
  GORIS_HD glm::vec3 forward() const { return glm::vec3(R[0][2], R[1][2], R[2][2]); }
  GORIS_HD bool has_distortion() const { return dist.any(); }

  // Pinhole projection of a camera-space point (no distortion) to continuous pixel coordinates.
  GORIS_HD glm::vec2 project_camera(const glm::vec3& p) const {
    return glm::vec2(fx * p.x / p.z + cx, fy * p.y / p.z + cy);
  }
  // Index (y * width + x) of the pixel a camera-space point projects into; -1 when it lies behind the
  // camera or outside the image.
  GORIS_HD long long pixel_of(const glm::vec3& p) const {
    if (!(p.z > 1e-6f)) return -1;
    const glm::vec2 uv = project_camera(p);
    if (!(uv.x >= 0.0f && uv.y >= 0.0f && uv.x < float(width) && uv.y < float(height))) return -1;
    return (long long)(uv.y) * width + (long long)(uv.x);
  }
  // World-space unit direction of the ray through continuous pixel coordinates (u, v), pinhole model.
  GORIS_HD glm::vec3 ray_direction(float u, float v) const {
    glm::vec3 d_cam((u - cx) / fx, (v - cy) / fy, 1.0f);
    return glm::normalize(glm::transpose(R) * d_cam);
  }
  // The same camera for an image resized to (w, h): intrinsics scale with the image.
  Camera resized(int w, int h) const {
    Camera c = *this;
    const float sx = float(w) / float(width), sy = float(h) / float(height);
    c.width = w;
    c.height = h;
    c.fx *= sx;
    c.cx *= sx;
    c.fy *= sy;
    c.cy *= sy;
    return c;
  }
};

}  // namespace goris
