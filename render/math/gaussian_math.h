#pragma once
// Per-Gaussian 3D maths shared by the CPU and CUDA rasterizers (and usable by the ray tracer): rotation from
// an unnormalised quaternion, the 3D covariance with Mip-Splatting's 3D filter, and hand-written
// vector-Jacobian products (VJPs) of each. Templated on the scalar type so that tests run them in double.
//
// Matrix gradients are full (every entry treated as independent): for y = f(M), dM[i][j] = dL/dM_ij.
// glm is column-major: m[c][r] is row r, column c; helpers below take (row, col) to keep formulas readable.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "core/compute/hd.h"

namespace goris::gmath {

// Unqualified maths calls pick the float overloads for float (host and device) and double for double.
using std::ceil;
using std::exp;
using std::log;
using std::max;
using std::min;
using std::sqrt;

template <class T> using Vec2 = glm::vec<2, T, glm::defaultp>;
template <class T> using Vec3 = glm::vec<3, T, glm::defaultp>;
template <class T> using Vec4 = glm::vec<4, T, glm::defaultp>;
template <class T> using Mat2 = glm::mat<2, 2, T, glm::defaultp>;
template <class T> using Mat3 = glm::mat<3, 3, T, glm::defaultp>;

// Element (row r, column c).
template <class M>
GORIS_HDI auto& at(M& m, int r, int c) { return m[c][r]; }
template <class M>
GORIS_HDI auto at(const M& m, int r, int c) { return m[c][r]; }

template <class T>
GORIS_HDI Mat3<T> diag3(const Vec3<T>& d) {
  Mat3<T> m(T(0));
  m[0][0] = d.x;
  m[1][1] = d.y;
  m[2][2] = d.z;
  return m;
}

template <class T>
GORIS_HDI T sigmoid(T x) { return T(1) / (T(1) + exp(-x)); }

// VJP of y = normalize(x): dx = (dy - y (y . dy)) / |x|.
template <class T>
GORIS_HDI Vec3<T> normalize_vjp(const Vec3<T>& x, const Vec3<T>& dy) {
  const T len = sqrt(glm::dot(x, x));
  const Vec3<T> y = x / len;
  return (dy - y * glm::dot(y, dy)) / len;
}

// ---- rotation ------------------------------------------------------------------------------------------
// q = (w, x, y, z) in q[0..3]; the rotation of q / |q|.
template <class T>
GORIS_HDI Mat3<T> quat_to_rotation(const Vec4<T>& q_raw) {
  const Vec4<T> q = q_raw / sqrt(glm::dot(q_raw, q_raw));
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  Mat3<T> R;
  at(R, 0, 0) = T(1) - T(2) * (y * y + z * z);
  at(R, 0, 1) = T(2) * (x * y - w * z);
  at(R, 0, 2) = T(2) * (x * z + w * y);
  at(R, 1, 0) = T(2) * (x * y + w * z);
  at(R, 1, 1) = T(1) - T(2) * (x * x + z * z);
  at(R, 1, 2) = T(2) * (y * z - w * x);
  at(R, 2, 0) = T(2) * (x * z - w * y);
  at(R, 2, 1) = T(2) * (y * z + w * x);
  at(R, 2, 2) = T(1) - T(2) * (x * x + y * y);
  return R;
}

// VJP of quat_to_rotation: dL/dq_raw from dL/dR.
template <class T>
GORIS_HDI Vec4<T> quat_to_rotation_vjp(const Vec4<T>& q_raw, const Mat3<T>& dR) {
  const T len = sqrt(glm::dot(q_raw, q_raw));
  const Vec4<T> q = q_raw / len;
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  const T d00 = at(dR, 0, 0), d01 = at(dR, 0, 1), d02 = at(dR, 0, 2);
  const T d10 = at(dR, 1, 0), d11 = at(dR, 1, 1), d12 = at(dR, 1, 2);
  const T d20 = at(dR, 2, 0), d21 = at(dR, 2, 1), d22 = at(dR, 2, 2);
  Vec4<T> dq;
  dq[0] = T(2) * (-z * d01 + y * d02 + z * d10 - x * d12 - y * d20 + x * d21);
  dq[1] = T(2) * (y * d01 + z * d02 + y * d10 - T(2) * x * d11 - w * d12 + z * d20 + w * d21 - T(2) * x * d22);
  dq[2] = T(2) * (-T(2) * y * d00 + x * d01 + w * d02 + x * d10 + z * d12 - w * d20 + z * d21 - T(2) * y * d22);
  dq[3] = T(2) * (-T(2) * z * d00 - w * d01 + x * d02 + w * d10 - T(2) * z * d11 + y * d12 + x * d20 + y * d21);
  // Through the normalisation.
  return (dq - q * glm::dot(q, dq)) / len;
}

// ---- covariance ----------------------------------------------------------------------------------------
// Variances along the Gaussian's axes: exp(2 log_scale) + filter3d_var (Mip-Splatting 3D filter).
template <class T>
GORIS_HDI Vec3<T> axis_variances(const Vec3<T>& log_scale, T filter3d_var) {
  return Vec3<T>(exp(T(2) * log_scale.x), exp(T(2) * log_scale.y), exp(T(2) * log_scale.z)) + Vec3<T>(filter3d_var);
}

// Opacity factor of the 3D filter: sqrt(det(S^2) / det(S^2 + f)) = prod_i s_i / sqrt(s_i^2 + f).
template <class T>
GORIS_HDI T filter3d_compensation(const Vec3<T>& log_scale, T filter3d_var) {
  if (filter3d_var == T(0)) return T(1);
  const Vec3<T> v = axis_variances(log_scale, filter3d_var);
  const Vec3<T> s2 = v - Vec3<T>(filter3d_var);
  return sqrt(s2.x * s2.y * s2.z / (v.x * v.y * v.z));
}

// dL/dlog_scale from dL/d(compensation): d log(comp) / d log s_i = f / (s_i^2 + f).
template <class T>
GORIS_HDI Vec3<T> filter3d_compensation_vjp(const Vec3<T>& log_scale, T filter3d_var, T dcomp) {
  if (filter3d_var == T(0)) return Vec3<T>(T(0));
  const Vec3<T> v = axis_variances(log_scale, filter3d_var);
  const T comp = filter3d_compensation(log_scale, filter3d_var);
  return Vec3<T>(filter3d_var / v.x, filter3d_var / v.y, filter3d_var / v.z) * (dcomp * comp);
}

// Sigma = R diag(v) R^T and its inverse R diag(1/v) R^T (the precision, used by the depth plane).
template <class T>
GORIS_HDI Mat3<T> covariance(const Mat3<T>& R, const Vec3<T>& v) { return R * diag3(v) * glm::transpose(R); }
template <class T>
GORIS_HDI Mat3<T> precision(const Mat3<T>& R, const Vec3<T>& v) {
  return R * diag3(Vec3<T>(T(1) / v.x, T(1) / v.y, T(1) / v.z)) * glm::transpose(R);
}

// VJP of M = R diag(d) R^T for a full gradient G = dL/dM: adds to dR and returns dL/dd.
template <class T>
GORIS_HDI Vec3<T> rdrt_vjp(const Mat3<T>& R, const Vec3<T>& d, const Mat3<T>& G, Mat3<T>& dR) {
  dR += (G + glm::transpose(G)) * R * diag3(d);
  const Mat3<T> RtGR = glm::transpose(R) * G * R;
  return Vec3<T>(RtGR[0][0], RtGR[1][1], RtGR[2][2]);
}

}  // namespace goris::gmath
