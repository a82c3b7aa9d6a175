#pragma once
// Maths of one ray hitting one Gaussian, shared by every tracing backend (Embree, LBVH on CPU and CUDA,
// brute force) and templated on the scalar type (float in production, double in the gradient tests).
//
// A Gaussian (mean mu, rotation R from an unnormalised (w,x,y,z) quaternion, axis scales s, opacity o) is
// hit by the ray o_r + t d at its point of maximum response (docs/design/maths.md, Tracing Gaussians):
//   M = S^-1 R^T,  a = M (o_r - mu),  b = M d,  t* = -(a.b)/(b.b),  p = a + t* b,
//   G = exp(-|p|^2 / 2),  alpha = min(0.99, o G);  a hit when o G >= 1/255 and t* > t_min.
// With Mip-Splatting's 3D filter the axis variances are s^2 + f and o is scaled by the compensation.
#include <limits>

#include "render/math/gaussian_math.h"

namespace goris::trace {

using namespace goris::gmath;

// The blending rule of the paper (the same constants as the rasterizer's).
// (Functions, not static data members: those cannot be ODR-used in device code.)
template <class T>
struct TraceConst {
  GORIS_HD static constexpr T alpha_max() { return T(0.99); }
  GORIS_HD static constexpr T alpha_min() { return T(1) / T(255); }
  GORIS_HD static constexpr T T_min() { return T(0.0001); }
};

// A Gaussian prepared for hit tests: M = S^-1 R^T row-major, its mean and effective opacity, and
// q2_max = 2 ln(255 opacity), the squared canonical distance beyond which it cannot reach 1/255.
template <class T>
struct TracePrim {
  T m[9];
  T mean[3];
  T opacity;
  T q2_max;
};

template <class T>
GORIS_HDI Vec3<T> load3(const T* p) { return Vec3<T>(p[0], p[1], p[2]); }

template <class T>
GORIS_HDI Mat3<T> prim_matrix(const TracePrim<T>& p) {
  Mat3<T> M;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) at(M, r, c) = p.m[3 * r + c];
  return M;
}

// The per-Gaussian quantities both make_prim and the parameter VJP need.
template <class T>
struct PrimParams {
  Mat3<T> R;
  Vec3<T> inv_s;  // 1 / sqrt(axis variance)
  Vec3<T> s;
  T sig;          // sigmoid(opacity logit)
  T comp;         // 3D filter opacity compensation (1 without filter)
};

template <class T>
GORIS_HDI PrimParams<T> prim_params(const T* log_scale, const T* quat, T logit, T f3d) {
  PrimParams<T> q;
  const Vec3<T> ls = load3(log_scale);
  const Vec3<T> v = axis_variances(ls, f3d);
  q.s = Vec3<T>(sqrt(v.x), sqrt(v.y), sqrt(v.z));
  q.inv_s = Vec3<T>(T(1) / q.s.x, T(1) / q.s.y, T(1) / q.s.z);
  q.R = quat_to_rotation(Vec4<T>(quat[0], quat[1], quat[2], quat[3]));
  q.sig = sigmoid(logit);
  q.comp = filter3d_compensation(ls, f3d);
  return q;
}

// Builds the prim of Gaussian parameters and its world-space box at the 1/255 response level (the ellipsoid
// o exp(-r^2/2) = 1/255 around the mean). A Gaussian that can never reach 1/255 gets an empty box lo > hi.
template <class T>
GORIS_HDI TracePrim<T> make_prim(const T* pos, const T* log_scale, const T* quat, T logit, T f3d, T* lo, T* hi) {
  const PrimParams<T> q = prim_params(log_scale, quat, logit, f3d);
  TracePrim<T> p;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.m[3 * r + c] = q.inv_s[r] * at(q.R, c, r);
  for (int k = 0; k < 3; ++k) p.mean[k] = pos[k];
  p.opacity = q.sig * q.comp;
  const T L = log(T(255) * p.opacity);
  p.q2_max = T(2) * L;
  if (!(L >= T(0))) {  // empty: leaves unions of boxes unchanged, and Embree skips it
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::numeric_limits<T>::infinity();
      hi[k] = -std::numeric_limits<T>::infinity();
    }
    return p;
  }
  const T r = sqrt(T(2) * L);
  for (int k = 0; k < 3; ++k) {
    // Half extent of the ellipsoid {mu + R S u : |u| <= r} along world axis k, padded against rounding.
    const T e = r * sqrt(at(q.R, k, 0) * at(q.R, k, 0) * q.s.x * q.s.x + at(q.R, k, 1) * at(q.R, k, 1) * q.s.y * q.s.y +
                         at(q.R, k, 2) * at(q.R, k, 2) * q.s.z * q.s.z);
    const T pad = e * T(1e-3) + (T(1) + (pos[k] < T(0) ? -pos[k] : pos[k])) * T(1e-6);
    lo[k] = pos[k] - e - pad;
    hi[k] = pos[k] + e + pad;
  }
  return p;
}

// Everything the forward and backward passes need from one ray-Gaussian evaluation.
template <class T>
struct HitEval {
  Vec3<T> x;  // o_r - mu
  Vec3<T> a, b, p;
  T D;        // b.b
  T t;        // t*
  T G;        // exp(-|p|^2/2)
  T alpha;    // min(0.99, o G)
};

// Evaluates the hit; false when the Gaussian is not hit (alpha < 1/255, t* <= t_min or a degenerate ray).
template <class T>
GORIS_HDI bool eval_hit(const TracePrim<T>& pr, const Vec3<T>& o, const Vec3<T>& d, T t_min, HitEval<T>& h) {
  h.t = h.G = h.alpha = T(0);
  h.p = Vec3<T>(T(0));
  const Mat3<T> M = prim_matrix(pr);
  h.x = o - load3(pr.mean);
  h.a = M * h.x;
  h.b = M * d;
  h.D = glm::dot(h.b, h.b);
  if (!(h.D > T(0))) return false;
  h.t = -glm::dot(h.a, h.b) / h.D;
  if (!(h.t > t_min)) return false;
  h.p = h.a + h.t * h.b;
  const T q2 = glm::dot(h.p, h.p);
  // Cheap rejection before exp, with a margin so that the decision below stays the exact one.
  if (!(q2 <= pr.q2_max * T(1.0001) + T(1e-6))) return false;
  h.G = exp(T(-0.5) * q2);
  const T A = pr.opacity * h.G;
  if (!(A >= TraceConst<T>::alpha_min())) return false;
  h.alpha = min(TraceConst<T>::alpha_max(), A);
  return true;
}

// Gradients of one hit with respect to the Gaussian (through M, mu and its effective opacity) and the ray.
template <class T>
struct HitGrad {
  Mat3<T> dM;       // dL/dM (full)
  Vec3<T> dmean;
  T dopacity;
  Vec3<T> dorigin;  // dL/do_r
  Vec3<T> ddir;     // dL/dd (geometry part only)
};

// VJP of (alpha, t*) given dL/dalpha and dL/dt*. No gradient flows through the 0.99 clamp.
template <class T>
GORIS_HDI HitGrad<T> eval_hit_vjp(const TracePrim<T>& pr, const Vec3<T>& d, const HitEval<T>& h, T dalpha, T dt) {
  HitGrad<T> g;
  g.dopacity = T(0);
  Vec3<T> gp(T(0));
  if (pr.opacity * h.G <= TraceConst<T>::alpha_max()) {
    g.dopacity = dalpha * h.G;
    const T dG = dalpha * pr.opacity;
    gp = -dG * h.G * h.p;  // dG/dp = -G p
  }
  // p = a + t b, t = -(a.b)/D
  const T dt_total = dt + glm::dot(gp, h.b);
  const Vec3<T> ga = gp - dt_total * h.b / h.D;
  const Vec3<T> gb = gp * h.t + dt_total * (-h.a - T(2) * h.t * h.b) / h.D;
  const Mat3<T> M = prim_matrix(pr);
  const Mat3<T> Mt = glm::transpose(M);
  const Vec3<T> gx = Mt * ga;
  g.dorigin = gx;
  g.dmean = -gx;
  g.ddir = Mt * gb;
  // a = M x, b = M d: dM_rc = ga_r x_c + gb_r d_c
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) at(g.dM, r, c) = ga[r] * h.x[c] + gb[r] * d[c];
  return g;
}

// Gradients of the Gaussian's parameters from dL/dM and dL/d(effective opacity).
template <class T>
struct ParamGrad {
  Vec3<T> dlog_scale;
  Vec4<T> dquat;
  T dlogit;
};

template <class T>
GORIS_HDI ParamGrad<T> prim_params_vjp(const T* log_scale, const T* quat, T logit, T f3d, const Mat3<T>& dM,
                                       T dopacity) {
  const PrimParams<T> q = prim_params(log_scale, quat, logit, f3d);
  const Vec3<T> ls = load3(log_scale);
  ParamGrad<T> g;
  // M_rc = inv_s_r R_cr
  Mat3<T> dR(T(0));
  Vec3<T> dinv_s(T(0));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      at(dR, c, r) += at(dM, r, c) * q.inv_s[r];
      dinv_s[r] += at(dM, r, c) * at(q.R, c, r);
    }
  g.dquat = quat_to_rotation_vjp(Vec4<T>(quat[0], quat[1], quat[2], quat[3]), dR);
  // inv_s = (exp(2 ls) + f)^-1/2: d inv_s / d ls = -inv_s exp(2 ls) / (exp(2 ls) + f) = -inv_s^3 exp(2 ls)
  for (int k = 0; k < 3; ++k) {
    const T e2 = exp(T(2) * ls[k]);
    g.dlog_scale[k] = -dinv_s[k] * q.inv_s[k] * q.inv_s[k] * q.inv_s[k] * e2;
  }
  // opacity = sigmoid(logit) * comp(ls)
  g.dlogit = dopacity * q.comp * q.sig * (T(1) - q.sig);
  g.dlog_scale += filter3d_compensation_vjp(ls, f3d, dopacity * q.sig);
  return g;
}

}  // namespace goris::trace
