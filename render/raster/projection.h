#pragma once
// EWA projection of one Gaussian to the screen (3DGS / gsplat conventions) plus RaDe-GS's ray-space depth
// plane and normal, and the hand-written VJP of all of it. Shared by the CPU and CUDA rasterizers.
//
// Ray space is (u, v, z): pixel coordinates and camera z. Linearised at the centre with the Jacobian J3
// (top rows: the usual EWA J with 3DGS's frustum clamp of x/z, y/z), the Gaussian's precision there is
// J3^-T Sc^-1 J3^-1, and J3^-1 maps the z axis of ray space to r = (x/z, y/z, 1). Along the ray through a
// pixel the response peaks at depth z_c + plane . (pixel - mean2d) with
//     h = Sc^-1 r,   plane = -(z/fx h_x, z/fy h_y) / (r . h),
// and the normal of that plane in camera space is parallel to h: normal = -normalize(h) (facing the camera).
// For a flat Gaussian the plane is exactly the Gaussian's own plane.
#include "core/io/camera.h"
#include "render/math/gaussian_math.h"
#include "render/raster/raster_types.h"

namespace goris::raster {

using namespace goris::gmath;

// The camera and settings converted to the scalar type once per render.
template <class T>
struct ProjectionParams {
  Mat3<T> W;  // world -> camera rotation
  Vec3<T> t;
  Vec3<T> center;  // camera centre in world space
  T fx, fy, cx, cy;
  int width, height;
  T lim_x_neg, lim_x_pos, lim_y_neg, lim_y_pos;  // frustum clamp of x/z and y/z (1.3 tan(fov/2) when centred)
  T filter2d_var, near_plane;
  bool filter2d_compensate;
};

template <class T>
ProjectionParams<T> make_projection_params(const Camera& cam, const RasterSettings& s) {
  ProjectionParams<T> p;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) p.W[c][r] = T(cam.R[c][r]);
  p.t = Vec3<T>(cam.t);
  p.center = -(glm::transpose(p.W) * p.t);
  p.fx = T(cam.fx), p.fy = T(cam.fy), p.cx = T(cam.cx), p.cy = T(cam.cy);
  p.width = cam.width, p.height = cam.height;
  const T tan_x = T(0.5) * T(cam.width) / p.fx, tan_y = T(0.5) * T(cam.height) / p.fy;
  p.lim_x_pos = (T(cam.width) - p.cx) / p.fx + T(0.3) * tan_x;
  p.lim_x_neg = p.cx / p.fx + T(0.3) * tan_x;
  p.lim_y_pos = (T(cam.height) - p.cy) / p.fy + T(0.3) * tan_y;
  p.lim_y_neg = p.cy / p.fy + T(0.3) * tan_y;
  p.filter2d_var = T(s.filter2d_var);
  p.near_plane = T(s.near_plane);
  p.filter2d_compensate = s.filter2d_compensate;
  return p;
}

// Parameters of one Gaussian, before activation.
template <class T>
struct GaussianParams {
  Vec3<T> mean, log_scale;
  Vec4<T> quat;  // (w, x, y, z)
  T opacity_logit;
  T filter3d_var;
};

template <class T>
GORIS_HDI GaussianParams<T> load_gaussian(const GaussiansT<T>& g, int i) {
  GaussianParams<T> p;
  p.mean = Vec3<T>(g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]);
  p.log_scale = Vec3<T>(g.log_scales[3 * i], g.log_scales[3 * i + 1], g.log_scales[3 * i + 2]);
  p.quat = Vec4<T>(g.rotations[4 * i], g.rotations[4 * i + 1], g.rotations[4 * i + 2], g.rotations[4 * i + 3]);
  p.opacity_logit = g.opacity_logits[i];
  p.filter3d_var = g.filter3d_var ? g.filter3d_var[i] : T(0);
  return p;
}

// Screen-space quantities of one Gaussian (the differentiable outputs of the projection).
template <class T>
struct Splat {
  Vec2<T> mean2d;
  Vec3<T> conic;  // a, b, c of inverse(S2 + filter2d_var I)
  T opacity;      // sigmoid(logit) * 3D filter compensation * 2D filter compensation
  T depth;        // camera z of the centre
  Vec2<T> plane;  // dz/du, dz/dv
  Vec3<T> normal;
};

// Intermediates shared by the forward and the VJP. The camera-space covariance M diag(v) M^T and precision
// M diag(1/v) M^T (M = W R: the Gaussian's axes in camera space) are never formed: A, h and their VJPs
// need only M's columns against a few vectors.
template <class T>
struct ProjectionInternals {
  Mat3<T> R;
  Mat3<T> M;      // W R
  Vec3<T> v;      // axis variances
  Vec3<T> tc;     // camera-space centre
  T ux, uy;       // clamped x/z, y/z
  bool clamp_x, clamp_y;
  Vec3<T> u0, u1; // M^T j0, M^T j1 (j0, j1: the rows of the EWA Jacobian J)
  Mat2<T> A;      // undilated 2D covariance J M diag(v) M^T J^T (full, symmetric)
  Vec3<T> mr;     // M^T r
  Vec3<T> h;      // precision times r: M (mr / v)
  T rh;           // r . h
  T sig, comp3, comp2, det_dil, det_raw;
};

// The rows j0, j1 of J = [[fx/z, 0, -fx ux/z], [0, fy/z, -fy uy/z]].
template <class T>
GORIS_HDI void ewa_jacobian(const ProjectionParams<T>& P, const ProjectionInternals<T>& in, Vec3<T>& j0, Vec3<T>& j1) {
  const T z = in.tc.z;
  j0 = Vec3<T>(P.fx / z, T(0), -P.fx * in.ux / z);
  j1 = Vec3<T>(T(0), P.fy / z, -P.fy * in.uy / z);
}

// Computes the splat; returns false when the Gaussian is culled (near plane, degenerate covariance).
template <class T>
GORIS_HDI bool project_gaussian(const GaussianParams<T>& g, const ProjectionParams<T>& P, Splat<T>& out,
                                ProjectionInternals<T>& in) {
  in.tc = P.W * g.mean + P.t;
  const T z = in.tc.z;
  if (!(z > P.near_plane)) return false;
  in.R = quat_to_rotation(g.quat);
  in.v = axis_variances(g.log_scale, g.filter3d_var);
  in.M = P.W * in.R;
  const Mat3<T> Mt = glm::transpose(in.M);
  const T rx = in.tc.x / z, ry = in.tc.y / z;
  in.clamp_x = rx < -P.lim_x_neg || rx > P.lim_x_pos;
  in.clamp_y = ry < -P.lim_y_neg || ry > P.lim_y_pos;
  in.ux = min(max(rx, -P.lim_x_neg), P.lim_x_pos);
  in.uy = min(max(ry, -P.lim_y_neg), P.lim_y_pos);
  // A = J Sc J^T = (J M) diag(v) (J M)^T, the rows of J M being u0, u1.
  Vec3<T> j0, j1;
  ewa_jacobian(P, in, j0, j1);
  in.u0 = Mt * j0;
  in.u1 = Mt * j1;
  const Vec3<T> vu0 = in.v * in.u0, vu1 = in.v * in.u1;
  const T a00 = glm::dot(in.u0, vu0), a01 = glm::dot(in.u0, vu1), a11 = glm::dot(in.u1, vu1);
  in.A = Mat2<T>(a00, a01, a01, a11);
  const T d00 = a00 + P.filter2d_var, d11 = a11 + P.filter2d_var;
  in.det_dil = d00 * d11 - a01 * a01;
  if (!(in.det_dil > T(0))) return false;
  in.det_raw = a00 * a11 - a01 * a01;
  out.conic = Vec3<T>(d11 / in.det_dil, -a01 / in.det_dil, d00 / in.det_dil);
  in.comp2 = P.filter2d_compensate ? sqrt(max(in.det_raw / in.det_dil, T(0))) : T(1);
  in.comp3 = filter3d_compensation(g.log_scale, g.filter3d_var);
  in.sig = sigmoid(g.opacity_logit);
  out.opacity = in.sig * in.comp3 * in.comp2;
  out.mean2d = Vec2<T>(P.fx * in.tc.x / z + P.cx, P.fy * in.tc.y / z + P.cy);
  out.depth = z;
  // Depth plane and normal from the precision along r: h = M diag(1/v) M^T r, r . h = sum mr^2 / v.
  const Vec3<T> r(in.ux, in.uy, T(1));
  in.mr = Mt * r;
  const Vec3<T> mr_v = in.mr / in.v;
  in.h = in.M * mr_v;
  in.rh = glm::dot(in.mr, mr_v);
  out.plane = Vec2<T>(-z / P.fx * in.h.x, -z / P.fy * in.h.y) / in.rh;
  out.normal = -glm::normalize(in.h);
  return true;
}

// 3 sigma of the larger eigenvalue of the dilated 2D covariance, rounded up (gsplat's 0.01 clamp).
template <class T>
GORIS_HDI int splat_radius(const ProjectionInternals<T>& in, T filter2d_var) {
  const T b = T(0.5) * (in.A[0][0] + in.A[1][1]) + filter2d_var;
  const T l1 = b + sqrt(max(b * b - in.det_dil, T(0.01)));
  return int(ceil(T(3) * sqrt(l1)));
}

// Gradients with respect to a splat's outputs.
template <class T>
struct SplatGrad {
  Vec2<T> mean2d{T(0)};
  Vec3<T> conic{T(0)};
  T opacity = T(0);
  T depth = T(0);
  Vec2<T> plane{T(0)};
  Vec3<T> normal{T(0)};
};

template <class T>
struct GaussianParamGrad {
  Vec3<T> mean{T(0)}, log_scale{T(0)};
  Vec4<T> quat{T(0)};
  T opacity_logit = T(0);
};

// VJP of project_gaussian (the Gaussian must not have been culled).
template <class T>
GORIS_HDI GaussianParamGrad<T> project_gaussian_vjp(const GaussianParams<T>& g, const ProjectionParams<T>& P,
                                                    const Splat<T>& s, const ProjectionInternals<T>& in,
                                                    const SplatGrad<T>& d) {
  GaussianParamGrad<T> out;
  const T z = in.tc.z;
  // Opacity = sig * comp3 * comp2.
  out.opacity_logit = d.opacity * in.comp3 * in.comp2 * in.sig * (T(1) - in.sig);
  const T dcomp3 = d.opacity * in.sig * in.comp2;
  const T dcomp2 = d.opacity * in.sig * in.comp3;
  // 2D covariance gradient (full 2x2) from the conic and the compensation.
  Mat2<T> dA(T(0));
  {
    const Mat2<T> Q(s.conic.x, s.conic.y, s.conic.y, s.conic.z);
    const Mat2<T> GQ(d.conic.x, T(0.5) * d.conic.y, T(0.5) * d.conic.y, d.conic.z);
    dA -= Q * GQ * Q;
    if (P.filter2d_compensate && in.comp2 > T(0)) {
      const T ddet_raw = dcomp2 * in.comp2 / (T(2) * in.det_raw);
      const T ddet_dil = -dcomp2 * in.comp2 / (T(2) * in.det_dil);
      const T a00 = in.A[0][0], a01 = in.A[1][0], a11 = in.A[1][1];
      const T d00 = a00 + P.filter2d_var, d11 = a11 + P.filter2d_var;
      dA[0][0] += ddet_raw * a11 + ddet_dil * d11;
      dA[1][1] += ddet_raw * a00 + ddet_dil * d00;
      dA[1][0] -= (ddet_raw + ddet_dil) * a01;
      dA[0][1] -= (ddet_raw + ddet_dil) * a01;
    }
  }
  // A = J Sc J^T with J rows j0, j1 and Sc = M diag(v) M^T. Only dA + dA^T matters (A is symmetric):
  // sym = [[s00, s01], [s01, s11]].
  Vec3<T> j0, j1;
  ewa_jacobian(P, in, j0, j1);
  const T s00 = T(2) * dA[0][0], s11 = T(2) * dA[1][1], s01 = dA[1][0] + dA[0][1];
  // dJ row i = sum_k sym[i][k] (Sc J^T)[:, k], with Sc j_k = M (v u_k).
  const Vec3<T> Sj0 = in.M * (in.v * in.u0), Sj1 = in.M * (in.v * in.u1);
  const Vec3<T> dj0 = Sj0 * s00 + Sj1 * s01;
  const Vec3<T> dj1 = Sj0 * s01 + Sj1 * s11;
  // Through Sc = M diag(v) M^T: with e_k = (sym U)_k (U: the rows u0, u1 of J M),
  //   dM[:, i] += v_i (j0 e0_i + j1 e1_i)   ((dSc + dSc^T) M diag(v), dSc = J^T dA J)
  //   dv_i = m_i^T dSc m_i = (u0_i e0_i + u1_i e1_i) / 2.
  const Vec3<T> e0 = in.u0 * s00 + in.u1 * s01, e1 = in.u0 * s01 + in.u1 * s11;
  Mat3<T> dM;
  for (int i = 0; i < 3; ++i) dM[i] = (j0 * e0[i] + j1 * e1[i]) * in.v[i];
  Vec3<T> dv = (in.u0 * e0 + in.u1 * e1) * T(0.5);
  // Depth plane and normal.
  const Vec3<T> r(in.ux, in.uy, T(1));
  Vec3<T> dh = normalize_vjp(in.h, -d.normal);
  T dz = d.depth;
  dz -= (d.plane.x * in.h.x / P.fx + d.plane.y * in.h.y / P.fy) / in.rh;
  dh.x -= d.plane.x * z / (P.fx * in.rh);
  dh.y -= d.plane.y * z / (P.fy * in.rh);
  const T drh = (d.plane.x * z / P.fx * in.h.x + d.plane.y * z / P.fy * in.h.y) / (in.rh * in.rh);
  Vec3<T> dr = in.h * drh;
  dh += r * drh;
  // h = Pc r with Pc = M diag(1/v) M^T (symmetric), dPc = dh r^T:
  //   dr += Pc dh;  dM[:, i] += (dh mr_i + r mdh_i) / v_i;  d(1/v_i) = mdh_i mr_i   (mdh = M^T dh).
  const Vec3<T> mdh = glm::transpose(in.M) * dh;
  const Vec3<T> inv_v = T(1) / in.v;
  dr += in.M * (mdh * inv_v);
  for (int i = 0; i < 3; ++i) dM[i] += (dh * in.mr[i] + r * mdh[i]) * inv_v[i];
  dv -= mdh * in.mr * inv_v * inv_v;
  // J entries -> z, ux, uy.
  T dux = dr.x - P.fx / z * dj0.z;
  T duy = dr.y - P.fy / z * dj1.z;
  dz += -P.fx / (z * z) * dj0.x - P.fy / (z * z) * dj1.y + P.fx * in.ux / (z * z) * dj0.z +
        P.fy * in.uy / (z * z) * dj1.z;
  Vec3<T> dtc(T(0));
  if (!in.clamp_x) {
    dtc.x += dux / z;
    dz -= dux * in.tc.x / (z * z);
  }
  if (!in.clamp_y) {
    dtc.y += duy / z;
    dz -= duy * in.tc.y / (z * z);
  }
  // mean2d = (fx x/z + cx, fy y/z + cy).
  dtc.x += d.mean2d.x * P.fx / z;
  dtc.y += d.mean2d.y * P.fy / z;
  dz -= (d.mean2d.x * P.fx * in.tc.x + d.mean2d.y * P.fy * in.tc.y) / (z * z);
  dtc.z += dz;
  const Mat3<T> Wt = glm::transpose(P.W);
  out.mean = Wt * dtc;
  // M = W R.
  const Mat3<T> dR = Wt * dM;
  const Vec3<T> s2 = in.v - Vec3<T>(g.filter3d_var);  // exp(2 log_scale)
  out.log_scale = dv * s2 * T(2) + filter3d_compensation_vjp(g.log_scale, g.filter3d_var, dcomp3);
  out.quat = quat_to_rotation_vjp(g.quat, dR);
  return out;
}

}  // namespace goris::raster
