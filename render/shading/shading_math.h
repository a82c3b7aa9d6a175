#pragma once
// Per-pixel maths of deferred shading, shared by the CPU and CUDA drivers, templated on the scalar type.
// Conventions: camera per core/io/camera.h (world-to-camera R, t; OpenCV axes; pixel centres at +0.5);
// d = unit view ray from the camera through the pixel (world); n = the G-buffer normal taken to world and
// normalised; omega_r = d - 2 (d . n) n (the paper's reflection of the viewing direction), so
// n . omega_r = -d . n is the cosine Schlick uses.
#include <cstddef>
#include <cmath>

#include <glm/glm.hpp>

#include "core/compute/hd.h"
#include "core/io/camera.h"

namespace goris::shading {

using std::sqrt;

template <class T> using Vec3 = glm::vec<3, T, glm::defaultp>;
template <class T> using Mat3 = glm::mat<3, 3, T, glm::defaultp>;

template <class T>
GORIS_HDI Vec3<T> plane3(const T* img, std::size_t P, std::size_t p) {
  return Vec3<T>(img[p], img[P + p], img[2 * P + p]);
}
template <class T>
GORIS_HDI void add_plane3(T* img, std::size_t P, std::size_t p, const Vec3<T>& v) {
  img[p] += v.x, img[P + p] += v.y, img[2 * P + p] += v.z;
}

// Geometry of one pixel: its view ray and the reflection of it about the surface normal.
template <class T>
struct PixelGeometry {
  Mat3<T> Rt;        // camera-to-world rotation
  Vec3<T> d_raw;     // R^T (x_n, y_n, 1): the ray scaled so that its camera z is 1 (x = centre + z d_raw)
  Vec3<T> d;         // unit view ray
  Vec3<T> n_raw;     // R^T n_cam (not normalised)
  Vec3<T> n;         // unit world normal
  bool degenerate;   // zero normal: n is taken as -d and gets no gradient
  Vec3<T> wr;        // reflection direction (unit)
  T cos_r;           // n . omega_r
};

template <class T>
GORIS_HDI PixelGeometry<T> pixel_geometry(const Camera& cam, int x, int y, const Vec3<T>& n_cam) {
  PixelGeometry<T> g;
  g.Rt = glm::transpose(Mat3<T>(cam.R));
  const Vec3<T> d_cam((T(x) + T(0.5) - T(cam.cx)) / T(cam.fx), (T(y) + T(0.5) - T(cam.cy)) / T(cam.fy), T(1));
  g.d_raw = g.Rt * d_cam;
  g.d = g.d_raw / sqrt(glm::dot(g.d_raw, g.d_raw));
  g.n_raw = g.Rt * n_cam;
  const T len2 = glm::dot(g.n_raw, g.n_raw);
  g.degenerate = !(len2 > T(1e-24));
  g.n = g.degenerate ? -g.d : g.n_raw / sqrt(len2);
  const T dn = glm::dot(g.d, g.n);
  g.wr = g.d - T(2) * dn * g.n;
  g.cos_r = -dn;
  return g;
}

// dL/d(n_cam) from dL/d(n), the unit world normal: through the normalisation and the rotation to world.
template <class T>
GORIS_HDI Vec3<T> unit_normal_vjp_to_camera_normal(const PixelGeometry<T>& g, const Vec3<T>& dn) {
  if (g.degenerate) return Vec3<T>(T(0));
  const T len = sqrt(glm::dot(g.n_raw, g.n_raw));
  const Vec3<T> dn_raw = (dn - g.n * glm::dot(g.n, dn)) / len;
  return glm::transpose(g.Rt) * dn_raw;
}

// dL/d(n_cam) from dL/d(omega_r), through the reflection.
template <class T>
GORIS_HDI Vec3<T> reflection_vjp_to_camera_normal(const PixelGeometry<T>& g, const Vec3<T>& dwr) {
  return unit_normal_vjp_to_camera_normal(g, T(-2) * (glm::dot(g.d, g.n) * dwr + glm::dot(dwr, g.n) * g.d));
}

// Schlick's weight (1 - cos)^5 on the clamped cosine. Treated as a constant in the backward pass, as the
// authors do (their n . omega_r is detached), so F's only gradient is to F0.
template <class T>
GORIS_HDI T schlick_weight(T cos_r) {
  const T c = cos_r < T(0) ? T(0) : (cos_r > T(1) ? T(1) : cos_r);
  const T m = T(1) - c;
  const T m2 = m * m;
  return m2 * m2 * m;
}

// Per-surface materials from the rasterized sums (divided by alpha when `normalize`).
template <class T>
struct Materials {
  T M, r;
  Vec3<T> f0;
  T scale;  // 1 / alpha or 1
};

template <class T>
GORIS_HDI Materials<T> read_materials(T M, const Vec3<T>& f0, T r, T alpha, bool normalize) {
  Materials<T> m;
  // Divide rather than multiply by 1 / alpha so that M = alpha gives exactly M_hat = 1 (C = D exactly).
  m.scale = normalize ? T(1) / alpha : T(1);
  m.M = normalize ? M / alpha : M;
  m.f0 = normalize ? f0 / alpha : f0;
  m.r = normalize ? r / alpha : r;
  return m;
}

}  // namespace goris::shading
