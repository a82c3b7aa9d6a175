#pragma once
// Real spherical harmonics up to degree 3 (the 3DGS basis and sign convention), their gradient with respect
// to the (unnormalised) direction, and the view-dependent colour of a Gaussian: SH(dir) + 0.5 clamped at 0,
// with dir = normalize(mean - camera centre). Coefficients are coefficient-major: sh[k][channel].
#include "render/math/gaussian_math.h"

namespace goris::gmath {

constexpr int sh_coeff_count(int degree) { return (degree + 1) * (degree + 1); }

namespace shc {
constexpr double C0 = 0.28209479177387814;
constexpr double C1 = 0.4886025119029199;
constexpr double C2[5] = {1.0925484305920792, -1.0925484305920792, 0.31539156525252005, -1.0925484305920792,
                          0.5462742152960396};
constexpr double C3[7] = {-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154,
                          -0.4570457994644658, 1.445305721320277, -0.5900435899266435};
}  // namespace shc

// Basis values b[k] at unit direction d, for k < sh_coeff_count(degree); when grad != null also
// grad[k] = d b[k] / d d (direction components treated as independent).
template <class T>
GORIS_HDI void sh_basis(int degree, const Vec3<T>& d, T* b, Vec3<T>* grad) {
  const T C1 = T(shc::C1);
  b[0] = T(shc::C0);
  if (grad) grad[0] = Vec3<T>(T(0));
  if (degree < 1) return;
  const T x = d.x, y = d.y, z = d.z;
  b[1] = -C1 * y;
  b[2] = C1 * z;
  b[3] = -C1 * x;
  if (grad) {
    grad[1] = Vec3<T>(T(0), -C1, T(0));
    grad[2] = Vec3<T>(T(0), T(0), C1);
    grad[3] = Vec3<T>(-C1, T(0), T(0));
  }
  if (degree < 2) return;
  const T xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
  const T c20 = T(shc::C2[0]), c21 = T(shc::C2[1]), c22 = T(shc::C2[2]), c23 = T(shc::C2[3]), c24 = T(shc::C2[4]);
  b[4] = c20 * xy;
  b[5] = c21 * yz;
  b[6] = c22 * (T(2) * zz - xx - yy);
  b[7] = c23 * xz;
  b[8] = c24 * (xx - yy);
  if (grad) {
    grad[4] = Vec3<T>(c20 * y, c20 * x, T(0));
    grad[5] = Vec3<T>(T(0), c21 * z, c21 * y);
    grad[6] = Vec3<T>(T(-2) * c22 * x, T(-2) * c22 * y, T(4) * c22 * z);
    grad[7] = Vec3<T>(c23 * z, T(0), c23 * x);
    grad[8] = Vec3<T>(T(2) * c24 * x, T(-2) * c24 * y, T(0));
  }
  if (degree < 3) return;
  const T c30 = T(shc::C3[0]), c31 = T(shc::C3[1]), c32 = T(shc::C3[2]), c33 = T(shc::C3[3]), c34 = T(shc::C3[4]),
          c35 = T(shc::C3[5]), c36 = T(shc::C3[6]);
  b[9] = c30 * y * (T(3) * xx - yy);
  b[10] = c31 * xy * z;
  b[11] = c32 * y * (T(4) * zz - xx - yy);
  b[12] = c33 * z * (T(2) * zz - T(3) * xx - T(3) * yy);
  b[13] = c34 * x * (T(4) * zz - xx - yy);
  b[14] = c35 * z * (xx - yy);
  b[15] = c36 * x * (xx - T(3) * yy);
  if (grad) {
    grad[9] = Vec3<T>(T(6) * c30 * xy, c30 * (T(3) * xx - T(3) * yy), T(0));
    grad[10] = Vec3<T>(c31 * yz, c31 * xz, c31 * xy);
    grad[11] = Vec3<T>(T(-2) * c32 * xy, c32 * (T(4) * zz - xx - T(3) * yy), T(8) * c32 * yz);
    grad[12] = Vec3<T>(T(-6) * c33 * xz, T(-6) * c33 * yz, c33 * (T(6) * zz - T(3) * xx - T(3) * yy));
    grad[13] = Vec3<T>(c34 * (T(4) * zz - T(3) * xx - yy), T(-2) * c34 * xy, T(8) * c34 * xz);
    grad[14] = Vec3<T>(T(2) * c35 * xz, T(-2) * c35 * yz, c35 * (xx - yy));
    grad[15] = Vec3<T>(c36 * (T(3) * xx - T(3) * yy), T(-6) * c36 * xy, T(0));
  }
}

// Colour of one Gaussian: sh points at its [16][3] coefficients. Returns max(SH(dir) + 0.5, 0).
template <class T>
GORIS_HDI Vec3<T> sh_color(int degree, const T* sh, const Vec3<T>& mean, const Vec3<T>& cam_center) {
  const Vec3<T> dir = glm::normalize(mean - cam_center);
  T b[16];
  sh_basis<T>(degree, dir, b, nullptr);
  Vec3<T> c(T(0.5));
  for (int k = 0; k < sh_coeff_count(degree); ++k) c += b[k] * Vec3<T>(sh[3 * k], sh[3 * k + 1], sh[3 * k + 2]);
  return Vec3<T>(max(c.x, T(0)), max(c.y, T(0)), max(c.z, T(0)));
}

// VJP of sh_color. `color` is the forward result (a clamped channel, colour <= 0, passes no gradient).
// Adds dL/dsh to dsh (may be null) and returns dL/dmean.
template <class T>
GORIS_HDI Vec3<T> sh_color_vjp(int degree, const T* sh, const Vec3<T>& mean, const Vec3<T>& cam_center,
                               const Vec3<T>& color, Vec3<T> dcolor, T* dsh) {
  dcolor.x = color.x > T(0) ? dcolor.x : T(0);
  dcolor.y = color.y > T(0) ? dcolor.y : T(0);
  dcolor.z = color.z > T(0) ? dcolor.z : T(0);
  const Vec3<T> raw = mean - cam_center;
  const Vec3<T> dir = glm::normalize(raw);
  T b[16];
  Vec3<T> g[16];
  sh_basis<T>(degree, dir, b, g);
  Vec3<T> ddir(T(0));
  for (int k = 0; k < sh_coeff_count(degree); ++k) {
    if (dsh) {
      dsh[3 * k] += b[k] * dcolor.x;
      dsh[3 * k + 1] += b[k] * dcolor.y;
      dsh[3 * k + 2] += b[k] * dcolor.z;
    }
    ddir += g[k] * (sh[3 * k] * dcolor.x + sh[3 * k + 1] * dcolor.y + sh[3 * k + 2] * dcolor.z);
  }
  return normalize_vjp(raw, ddir);
}

}  // namespace goris::gmath
