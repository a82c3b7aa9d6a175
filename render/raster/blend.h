#pragma once
// Per-(pixel, Gaussian) maths of the blend, shared by the CPU tile loops and the CUDA per-pixel kernels,
// so both apply the same skip / stop rule (up to exp rounding: libm / CUDA expf / the CPU lanes' exp). The
// 3DGS rule: alpha = min(0.99, o exp(power)), skip when power > 0 or alpha < 1/255, stop before
// T (1 - alpha) < 1e-4. The formulas take the per-pixel values as a type S of their own: the scalar T on
// CUDA and in eval_hit, or a pack of SIMD lanes (one pixel each) in the CPU tile loops (lanes_cpu.h).
#include "render/math/gaussian_math.h"

namespace goris::raster {

using namespace goris::gmath;

constexpr int kMaxExtras = 16;                      // extra channels a render can carry
constexpr int kBaseChannels = 7;                    // colour 3, depth 1, normal 3
constexpr int kMaxChannels = kBaseChannels + kMaxExtras;
// Blended channel c of a Gaussian: [0,3) colour, 3 depth (on its plane, varies per pixel), [4,7) normal,
// [7, 7 + K) extras.
constexpr int kChDepth = 3, kChNormal = 4, kChExtras = 7;

// Per-(tile, Gaussian) partial gradient slot: dL/d of the Gaussian's screen-space quantities.
constexpr int kGMean = 0, kGConic = 2, kGOpacity = 5, kGColor = 6, kGDepth = 9, kGPlane = 10, kGNormal = 12,
              kGExtras = 15;
GORIS_HDI int grad_slot_stride(int n_extras) { return kGExtras + n_extras; }

// Packed per-Gaussian record of the blend (RasterStateT::packed): everything a tile loop reads, one line.
// kPkTwoL holds alpha_two_L(opacity), computed once per Gaussian for the CPU loops' pixel ranges.
constexpr int kPackedStride = 16;
constexpr int kPkMean = 0, kPkConic = 2, kPkOpacity = 5, kPkDepth = 6, kPkPlane = 7, kPkColor = 9, kPkNormal = 12,
              kPkTwoL = 15;

template <class T>
struct BlendConst {
  static constexpr T alpha_max = T(0.99);
  static constexpr T alpha_min = T(1) / T(255);
  static constexpr T T_min = T(0.0001);
};

// Result of evaluating one Gaussian at one pixel centre.
template <class T>
struct PixelHit {
  T alpha;   // 0 when skipped
  T G;       // exp(power)
  T dx, dy;  // mean2d - pixel centre
};

// The Gaussian's exponent at (dx, dy) = mean - pixel centre.
template <class T, class S>
GORIS_HDI S hit_power(const Vec3<T>& conic, S dx, S dy) {
  return T(-0.5) * (conic.x * dx * dx + conic.z * dy * dy) - conic.y * dx * dy;
}

template <class T>
GORIS_HDI PixelHit<T> eval_hit(const Vec2<T>& mean, const Vec3<T>& conic, T opacity, T px, T py) {
  PixelHit<T> h;
  h.dx = mean.x - px;
  h.dy = mean.y - py;
  const T power = hit_power(conic, h.dx, h.dy);
  h.alpha = T(0);
  h.G = T(0);
  if (power > T(0)) return h;
  h.G = exp(power);
  const T oG = opacity * h.G;
  const T a = oG < BlendConst<T>::alpha_max ? oG : BlendConst<T>::alpha_max;  // min(0.99, o G)
  if (a < BlendConst<T>::alpha_min) return h;
  h.alpha = a;
  return h;
}

// Where a splat can pass alpha >= 1/255: the ellipse a dx^2 + 2 b dx dy + c dy^2 <= 2 L with
// L = ln(255 o) (dx, dy = mean - pixel centre), widened a little against rounding so that pixels outside
// are certain to fail the per-pixel test. The CPU loops visit only these pixels; CUDA tests every pixel.
template <class T>
struct AlphaEllipse {
  T two_L;         // 2 L, widened
  T det;           // a c - b^2
  bool unbounded;  // ill-conditioned conic: test every pixel
};

// The widened 2 L of a splat's opacity, or -1 when no pixel can pass alpha >= 1/255 (otherwise > -1e-5).
template <class T>
GORIS_HDI T alpha_two_L(T opacity) {
  const T L = log(T(255) * opacity);
  if (!(L > T(-1e-3))) return T(-1);
  return T(2) * (L * T(1.001) + T(1e-3));
}

// The ellipse from a splat's conic and alpha_two_L(opacity); false when the splat reaches no pixel.
template <class T>
GORIS_HDI bool alpha_ellipse(const Vec3<T>& conic, T two_L, AlphaEllipse<T>& e) {
  if (!(two_L > T(-0.5))) return false;
  e.two_L = two_L;
  e.det = conic.x * conic.z - conic.y * conic.y;
  e.unbounded = !(e.det > T(1e-12) * conic.x * conic.z) || !(conic.x > T(0));
  return true;
}

// Pixel-centre y range [y_lo, y_hi] of the ellipse around mean.y.
template <class T>
GORIS_HDI void alpha_rows(const Vec2<T>& mean, const Vec3<T>& conic, const AlphaEllipse<T>& e, T& y_lo, T& y_hi) {
  if (e.unbounded) {
    y_lo = T(-1e30), y_hi = T(1e30);
    return;
  }
  const T ey = sqrt(e.two_L * conic.x / e.det) + T(0.05);
  y_lo = mean.y - ey, y_hi = mean.y + ey;
}

// The pixel-centre x range of a bounded ellipse on the row at dy = mean.y - py, in two steps (S may be
// a pack of SIMD lanes, one row each): alpha_span_q is negative when the row misses the ellipse;
// otherwise alpha_span_ends gives [x_lo, x_hi] from sqrt(q).
template <class T, class S>
GORIS_HDI S alpha_span_q(const Vec3<T>& conic, const AlphaEllipse<T>& e, S dy) {
  return conic.y * conic.y * dy * dy - conic.x * (conic.z * dy * dy - e.two_L);
}
template <class T, class S>
GORIS_HDI void alpha_span_ends(const Vec2<T>& mean, const Vec3<T>& conic, S dy, S sqrt_q, S& x_lo, S& x_hi) {
  // dx = mean.x - px in [c - r, c + r]
  const S r = sqrt_q / conic.x + T(0.05), c = -conic.y * dy / conic.x;
  x_lo = mean.x - c - r, x_hi = mean.x - c + r;
}

// Depth of a Gaussian's plane at a pixel: z + plane . (pixel - mean2d) = z - plane . (dx, dy).
template <class T, class S>
GORIS_HDI S plane_depth(T z, const Vec2<T>& plane, S dx, S dy) { return z - plane.x * dx - plane.y * dy; }

// Backward of the per-pixel Gaussian evaluation given dL/dalpha: adds to the mean2d, conic and opacity
// slots of `g`. No gradient flows through the 0.99 clamp.
template <class T>
GORIS_HDI void eval_hit_vjp(const Vec3<T>& conic, T opacity, const PixelHit<T>& h, T dalpha, T* g) {
  if (opacity * h.G > BlendConst<T>::alpha_max) return;
  g[kGOpacity] += dalpha * h.G;
  const T dpower = dalpha * opacity * h.G;
  g[kGConic + 0] += T(-0.5) * h.dx * h.dx * dpower;
  g[kGConic + 1] += -h.dx * h.dy * dpower;
  g[kGConic + 2] += T(-0.5) * h.dy * h.dy * dpower;
  g[kGMean + 0] += (-conic.x * h.dx - conic.y * h.dy) * dpower;
  g[kGMean + 1] += (-conic.z * h.dy - conic.y * h.dx) * dpower;
}

// Backward of a plane depth value at one pixel given its gradient gd.
template <class T>
GORIS_HDI void plane_depth_vjp(const Vec2<T>& plane, T dx, T dy, T gd, T* g) {
  g[kGDepth] += gd;
  g[kGPlane + 0] -= gd * dx;
  g[kGPlane + 1] -= gd * dy;
  g[kGMean + 0] -= gd * plane.x;
  g[kGMean + 1] -= gd * plane.y;
}

// The same two backward steps summed over many pixels, with the splat's constants (conic, opacity, plane)
// taken out of the sums: per pixel, hit_moments_add accumulates nine moments of q = G dL/dalpha and of
// the depth gradient gd; hit_moments_grad turns them into the slots eval_hit_vjp and plane_depth_vjp would
// have summed (equal up to rounding), with fewer operations per pixel.
template <class S>
struct HitMoments {
  S q{}, qx{}, qy{}, qxx{}, qxy{}, qyy{};  // sums of q, q dx, q dy, q dx^2, q dx dy, q dy^2
  S gd{}, gdx{}, gdy{};                    // sums of gd, gd dx, gd dy
};

// dalpha: dL/dalpha, 0 where the 0.99 clamp is active (as in eval_hit_vjp); gd: dL/d(plane depth).
template <class S>
GORIS_HDI void hit_moments_add(HitMoments<S>& m, S G, S dx, S dy, S dalpha, S gd) {
  const S q = dalpha * G, qx = q * dx, qy = q * dy;
  m.q += q;
  m.qx += qx;
  m.qy += qy;
  m.qxx += qx * dx;
  m.qxy += qx * dy;
  m.qyy += qy * dy;
  m.gd += gd;
  m.gdx += gd * dx;
  m.gdy += gd * dy;
}

// Adds the gradients of the summed pixels to the mean2d, conic, opacity, depth and plane slots of g.
template <class T>
GORIS_HDI void hit_moments_grad(const HitMoments<T>& m, const Vec3<T>& conic, T opacity, const Vec2<T>& plane,
                                T* g) {
  g[kGOpacity] += m.q;
  g[kGConic + 0] += T(-0.5) * opacity * m.qxx;
  g[kGConic + 1] += -opacity * m.qxy;
  g[kGConic + 2] += T(-0.5) * opacity * m.qyy;
  g[kGMean + 0] += -opacity * (conic.x * m.qx + conic.y * m.qy) - plane.x * m.gd;
  g[kGMean + 1] += -opacity * (conic.z * m.qy + conic.y * m.qx) - plane.y * m.gd;
  g[kGDepth] += m.gd;
  g[kGPlane + 0] -= m.gdx;
  g[kGPlane + 1] -= m.gdy;
}

}  // namespace goris::raster
