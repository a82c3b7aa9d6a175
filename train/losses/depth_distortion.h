#pragma once
// Depth distortion (2DGS, used by RaDe-GS and the paper's stage 1, S1.5): per pixel, the blending weights
// w_i = alpha_i T_i should sit at one depth, not spread along the ray. With m_i a Gaussian's NDC-like depth,
//
//   L_pixel = sum_{i<j} w_i w_j (m_i - m_j)^2 = A M2 - M1^2,   A = sum w_i, M1 = sum w_i m_i, M2 = sum w_i m_i^2
//
// (the pair sum equals the weighted variance times A^2), so three blended images give the loss exactly and
// its gradient flows back through the ordinary blending backward: dL/dA = M2, dL/dM1 = -2 M1, dL/dM2 = A.
// Why it matters here: over a glossy table a radiance model learns reflections as a "mirror world" seen
// through a half-transparent table top - two surfaces on one ray, exactly what this loss penalises.
//
// m is the depth of the Gaussian's centre (not of its depth plane at the pixel, as 2DGS's ray-splat depth):
// the blended moments need one value per Gaussian. m = f/(f-n) (1 - n/z), 2DGS's NDC map, with n and f
// tied to the scene's extent so the paper's weight (1000 for bounded scenes) means the same at any scale.
#include <algorithm>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"

namespace goris {

struct DistortionDepthRange {
  double near = 0, far = 0;
  // n = extent / 20, f = 25 extent: NeRF-synthetic's camera radius ~4 gives 2DGS's n = 0.2, f = 100.
  static DistortionDepthRange for_extent(double extent) { return {extent / 20.0, extent * 25.0}; }
};

// Camera-space z of a world point, in T (the FD tests run in double): forward() . x + t.z.
template <class T>
T camera_z(const Camera& camera, const T* x) {
  const glm::vec3 row = camera.forward();
  return T(row.x) * x[0] + T(row.y) * x[1] + T(row.z) * x[2] + T(camera.t.z);
}

// NDC-like depth of camera z and its derivative; 0 (and no gradient) in front of the near plane.
template <class T>
T distortion_depth(T z, const DistortionDepthRange& r, T* dm_dz = nullptr) {
  const T n = T(r.near), f = T(r.far), s = f / (f - n);
  if (!(z > n)) {
    if (dm_dz) *dm_dz = T(0);
    return T(0);
  }
  if (dm_dz) *dm_dz = s * n / (z * z);
  return s * (T(1) - n / z);
}

// mean over pixels of w (A M2 - M1^2) (the pair sum clamped at 0 against rounding; w = pixel_weight[p], or
// 1 when it is null); adds weight x the gradients into g_* (each [hw], any may be null).
template <class T>
double depth_distortion_loss(const T* A, const T* M1, const T* M2, std::size_t hw, T* g_A, T* g_M1, T* g_M2,
                             T weight, const T* pixel_weight = nullptr) {
  if (hw == 0) return 0.0;
  double sum = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    const T w = pixel_weight ? pixel_weight[p] : T(1);
    const T s = weight * w / T(hw);
    sum += double(w) * std::max(double(A[p] * M2[p] - M1[p] * M1[p]), 0.0);
    if (g_A) g_A[p] += s * M2[p];
    if (g_M1) g_M1[p] += s * T(-2) * M1[p];
    if (g_M2) g_M2[p] += s * A[p];
  }
  return sum / double(hw);
}

// The per-Gaussian values the blend carries: [N][2] = (d, d^2) with d = m - center for each centre seen by
// `camera`. The loss does not change with `center` (a variance), but float does: A M2 - M1^2 of uncentred
// m ~ 0.95 cancels to noise, so the pass centres on the view's median depth (distortion_center).
template <class T>
void distortion_moments(const T* positions, std::size_t count, const Camera& camera, const DistortionDepthRange& r,
                        T center, T* out) {
  for (std::size_t i = 0; i < count; ++i) {
    const T d = distortion_depth(camera_z(camera, positions + 3 * i), r) - center;
    out[2 * i] = d;
    out[2 * i + 1] = d * d;
  }
}

// Back-propagates dL/d(d, d^2) per Gaussian ([N][2]) into dL/dposition ([N][3], +=); `center` as given to
// distortion_moments (a constant).
template <class T>
void distortion_moments_backward(const T* positions, std::size_t count, const Camera& camera,
                                 const DistortionDepthRange& r, T center, const T* g_moments, T* g_positions) {
  const glm::vec3 row = camera.forward();
  for (std::size_t i = 0; i < count; ++i) {
    T dm = 0;
    const T d = distortion_depth(camera_z(camera, positions + 3 * i), r, &dm) - center;
    const T gz = (g_moments[2 * i] + T(2) * d * g_moments[2 * i + 1]) * dm;
    g_positions[3 * i + 0] += gz * T(row.x);
    g_positions[3 * i + 1] += gz * T(row.y);
    g_positions[3 * i + 2] += gz * T(row.z);
  }
}

// The median depth m of the centres in front of the near plane (0 if none): where distortion_moments centres.
template <class T>
T distortion_center(const T* positions, std::size_t count, const Camera& camera, const DistortionDepthRange& r) {
  std::vector<T> m;
  m.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const T z = camera_z(camera, positions + 3 * i);
    if (z > T(r.near)) m.push_back(distortion_depth(z, r));
  }
  if (m.empty()) return T(0);
  std::nth_element(m.begin(), m.begin() + m.size() / 2, m.end());
  return m[m.size() / 2];
}

}  // namespace goris
