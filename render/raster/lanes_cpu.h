#pragma once
// SIMD lane packs for the CPU tile loops: a few neighbouring pixels of one tile row evaluated together with
// GCC/Clang vector extensions (SSE2 on baseline x86-64, NEON on ARM): 4 float lanes or 2 double lanes.
// Each lane does the operations of the scalar formula in the same order, so it gets the scalar result;
// only exp differs: float lanes use lane_exp below (at most ~1 ulp from the true exp; libm's expf is
// correctly rounded nearly everywhere), double lanes call libm. CPU only: never included by CUDA code.
#include <cmath>
#include <cstdint>
#include <cstring>

namespace goris::raster {

template <class T>
struct Lanes;

template <>
struct Lanes<float> {
  static constexpr int N = 4;
  typedef float V __attribute__((vector_size(16)));
  typedef std::int32_t M __attribute__((vector_size(16)));  // lane comparison: all ones or zero
};

template <>
struct Lanes<double> {
  static constexpr int N = 2;
  typedef double V __attribute__((vector_size(16)));
  typedef std::int64_t M __attribute__((vector_size(16)));
};

template <class T>
using LaneV = typename Lanes<T>::V;
template <class T>
using LaneM = typename Lanes<T>::M;

template <class T>
inline LaneV<T> lane_load(const T* p) {
  LaneV<T> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <class T>
inline void lane_store(T* p, LaneV<T> v) { std::memcpy(p, &v, sizeof v); }

template <class T>
inline LaneV<T> lane_splat(T s) { return LaneV<T>{} + s; }

// Lane j = first + j.
template <class T>
inline LaneV<T> lane_iota(T first) {
  LaneV<T> v;
  for (int j = 0; j < Lanes<T>::N; ++j) v[j] = first + T(j);
  return v;
}

// m ? a : b per lane.
template <class V, class M>
inline V lane_select(M m, V a, V b) { return (V)(((M)a & m) | ((M)b & ~m)); }

// Lane masks <-> bit j of an integer for lane j.
template <class T>
inline LaneM<T> lane_mask(unsigned bits) {
  LaneM<T> b;
  for (int j = 0; j < Lanes<T>::N; ++j) b[j] = decltype(b[0] + 0)(1) << j;
  return (b & decltype(b[0] + 0)(bits)) != 0;
}

template <class T>
inline unsigned lane_bits(LaneM<T> m) {
#if defined(__SSE2__)
  if constexpr (sizeof(T) == 4)
    return unsigned(__builtin_ia32_movmskps((__attribute__((vector_size(16))) float)m));
  else
    return unsigned(__builtin_ia32_movmskpd((__attribute__((vector_size(16))) double)m));
#else
  unsigned b = 0;
  for (int j = 0; j < Lanes<T>::N; ++j) b |= unsigned(m[j] != 0) << j;
  return b;
#endif
}

template <class T>
inline LaneV<T> lane_sqrt(LaneV<T> v) {
#if defined(__SSE2__)
  if constexpr (sizeof(T) == 4)
    return __builtin_ia32_sqrtps(v);
  else
    return __builtin_ia32_sqrtpd(v);
#else
  for (int j = 0; j < Lanes<T>::N; ++j) v[j] = std::sqrt(v[j]);
  return v;
#endif
}

// Truncation toward zero to integer lanes (values must fit) and back.
template <class T>
inline LaneM<T> lane_trunc(LaneV<T> v) { return __builtin_convertvector(v, LaneM<T>); }
template <class T>
inline LaneV<T> lane_float(LaneM<T> v) { return __builtin_convertvector(v, LaneV<T>); }

// Bit x set where row[x] > k, for the kTileSize (16) entries of a tile row.
inline std::uint32_t row_mask_above(const std::uint32_t* row, std::uint32_t k) {
  typedef std::uint32_t U __attribute__((vector_size(16)));
  typedef float F __attribute__((vector_size(16)));
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) {
    U v;
    std::memcpy(&v, row + 4 * i, sizeof v);
    const auto gt = v > k;
#if defined(__SSE2__)
    bits |= std::uint32_t(__builtin_ia32_movmskps((F)gt)) << (4 * i);
#else
    for (int j = 0; j < 4; ++j) bits |= std::uint32_t(gt[j] != 0) << (4 * i + j);
#endif
  }
  return bits;
}

// 2^x per integer lane, 0 <= x <= 30: the exponent field of a float (double) with the value 2^x, converted.
template <class T>
inline LaneM<T> lane_pow2(LaneM<T> x) {
  constexpr int mant = sizeof(T) == 4 ? 23 : 52, bias = sizeof(T) == 4 ? 127 : 1023;
  return lane_trunc<T>((LaneV<T>)((x + bias) << mant));
}

// Lanes where the 32-bit integer p[j] equals v.
template <class T>
inline LaneM<T> lane_equal(const std::uint32_t* p, std::uint32_t v) {
  if constexpr (sizeof(T) == 4) {
    LaneM<T> x;
    std::memcpy(&x, p, sizeof x);
    return x == std::int32_t(v);
  } else {
    LaneM<T> r;
    for (int j = 0; j < Lanes<T>::N; ++j) r[j] = p[j] == v ? -1 : 0;
    return r;
  }
}

// p[j] = m[j] ? v : p[j] for the lanes' 32-bit integers, without a branch per lane.
template <class T>
inline void lane_store_where(std::uint32_t* p, LaneM<T> m, std::uint32_t v) {
  if constexpr (sizeof(T) == 4) {
    LaneM<T> old;
    std::memcpy(&old, p, sizeof old);
    const LaneM<T> r = lane_select(m, LaneM<T>{} + std::int32_t(v), old);
    std::memcpy(p, &r, sizeof r);
  } else {
    for (int j = 0; j < Lanes<T>::N; ++j) p[j] = m[j] ? v : p[j];
  }
}

// Sum of the lanes in lane order (a fixed order: the result does not depend on threads or machines).
template <class T>
inline T lane_sum(LaneV<T> v) {
  T s = v[0];
  for (int j = 1; j < Lanes<T>::N; ++j) s += v[j];
  return s;
}

// exp(x) for x <= 0, per lane. Float: 2^n e^r with n = round(x / ln 2) and |r| <= ln 2 / 2 (ln 2 split in
// two parts, the first exact in a product with n), e^r from its Taylor series to r^7 (truncation below
// 1e-8 relative); results below e^-87 are not needed (alpha < 1/255 long before) and come out tiny, not 0.
inline Lanes<float>::V lane_exp(Lanes<float>::V x) {
  using V = Lanes<float>::V;
  using M = Lanes<float>::M;
  x = lane_select(x < -87.f, lane_splat(-87.f), x);
  constexpr float kRound = 12582912.f;  // 1.5 * 2^23: adding it rounds to an integer (|value| < 2^22)
  const V t = x * 1.44269504088896341f + kRound;
  const V n = t - kRound;
  const V r = (x - n * 0.693359375f) - n * -2.12194440054690583e-4f;
  // e^r = 1 + (r + r^2 q(r)): the small part first, so that its rounding is small next to the final 1 +;
  // q in Estrin's scheme (pairs, then powers of r^2) for a short dependency chain.
  const V r2 = r * r;
  const V q01 = r * (1.f / 6.f) + 0.5f, q23 = r * (1.f / 120.f) + (1.f / 24.f),
          q45 = r * (1.f / 5040.f) + (1.f / 720.f);
  const V q = q01 + r2 * (q23 + r2 * q45);
  const V p = (r + r2 * q) + 1.f;
  const M ni = (M)t - 0x4B400000;  // bits of kRound + n  ->  n
  return p * (V)((ni + 127) << 23);
}

inline Lanes<double>::V lane_exp(Lanes<double>::V x) {
  Lanes<double>::V r;
  for (int j = 0; j < Lanes<double>::N; ++j) r[j] = std::exp(x[j]);
  return r;
}

}  // namespace goris::raster
