#pragma once
// Pieces the splat codecs (core/io/splat_*.cpp) share: bounds-checked little-endian reading, byte
// quantization, opacity activation, gzip through zlib.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/io/ply.h"
#include "core/util/error.h"

namespace goris::splat_detail {

constexpr float kShC0 = 0.28209479177387814f;
constexpr float kSqrtHalf = 0.70710678118654752f;  // bound of every unit-quaternion component but the largest

inline float sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }
// The logit of a decoded alpha, kept finite: alphas of 0 and 1 (a byte of 0 or 255) become half a byte
// step inside the range, so every decoded opacity is a number the PLY writer and the renderer accept.
inline float logit_of_alpha(float a) {
  const float lo = 0.5f / 255.0f;
  a = std::clamp(a, lo, 1.0f - lo);
  return std::log(a / (1.0f - a));
}
// round(x) clamped to 0..255 (NaN gives 0).
inline uint8_t to_byte(float x) {
  if (!(x > 0.0f)) return 0;
  return uint8_t(std::min(255.0f, std::round(x)));
}

inline void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(uint8_t(v >> (8 * b)));
}
inline void put_f32(std::vector<uint8_t>& out, float v) {
  uint32_t u;
  std::memcpy(&u, &v, 4);
  put_u32(out, u);
}
inline uint32_t get_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
inline float get_f32(const uint8_t* p) {
  const uint32_t u = get_u32(p);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// An empty model of `count` Gaussians at `degree` with every array sized (normals and extras empty).
inline GaussianPly sized_model(size_t count, int degree) {
  GaussianPly g;
  g.count = count;
  g.sh_degree = degree;
  g.positions.resize(count * 3);
  g.f_dc.resize(count * 3);
  g.f_rest.resize(count * GaussianPly::rest_per_gaussian(degree));
  g.opacity.resize(count);
  g.scales.resize(count * 3);
  g.rotations.resize(count * 4);
  return g;
}

// Checks `g` can be encoded: consistent arrays and finite standard values (the first bad one named).
void check_encodable(const GaussianPly& g, const std::string& name);
// Checks a decoded model's values are finite (a file's ranges can overflow a float when expanded).
void check_decoded(const GaussianPly& g, const std::string& name);
// The normalised w x y z quaternion of Gaussian i (identity when it is zero).
void unit_quaternion(const GaussianPly& g, size_t i, float q[4]);

// gzip (RFC 1952) of `data`; decompression throws goris::Error(name, ...) for a truncated or corrupt
// stream and for output beyond max_out bytes; with prefix_only it returns the first max_out bytes instead.
std::vector<uint8_t> gzip_compress(const std::vector<uint8_t>& data, const std::string& name);
std::vector<uint8_t> gzip_decompress(const uint8_t* data, size_t size, size_t max_out, const std::string& name,
                                     bool prefix_only = false);

}  // namespace goris::splat_detail
