// Niantic SPZ versions 2 and 3 (core/io/splat_formats.h has the layout and quantization): one gzip
// stream of a 16-byte header and the attributes, each for all Gaussians in turn.
#include <array>
#include <cmath>

#include "core/io/splat_codec.h"
#include "core/io/splat_formats.h"

namespace goris {
namespace {
using namespace splat_detail;

constexpr uint32_t kMagic = 0x5053474e;  // "NGSP"
constexpr size_t kHeaderBytes = 16;
constexpr uint8_t kFlagAntialiased = 0x1, kFlagExtensions = 0x2;
constexpr float kColorScale = 0.15f;  // SPZ's DC scale: wider than SH_C0 so colours beyond 0..1 survive
constexpr uint32_t kMaxPoints = 200'000'000;

// PLY (RDF) <-> SPZ (RUB): y and z change sign. For a rotation that is conjugation by the 180-degree turn
// about x: the quaternion's y and z change sign. SH coefficient k >= 1 changes sign when its basis
// function is odd in y and z taken together (3DGS's real SH order: y z x, xy yz z2 xz x2-y2, ...).
constexpr float kFlipP[3] = {1, -1, -1};
constexpr float kFlipSh[15] = {-1, -1, 1, -1, 1, 1, -1, 1, -1, 1, -1, -1, 1, -1, 1};

size_t sh_coeffs(int degree) { return size_t((degree + 1) * (degree + 1) - 1); }

size_t payload_bytes(size_t n, int degree, uint32_t version) {
  return n * (9 + 1 + 3 + 3 + (version >= 3 ? 4 : 3) + sh_coeffs(degree) * 3);
}

uint8_t quantize_sh(float x, int bucket) {
  int q = int(std::lround(x * 128.0f)) + 128;
  q = (q + bucket / 2) / bucket * bucket;
  return uint8_t(std::clamp(q, 0, 255));
}

// Smallest three of x y z w (SPZ's component order): 2 bits for the largest, 3 x (sign + 9 bits).
uint32_t pack_smallest_three(const float xyzw[4]) {
  int largest = 0;
  for (int k = 1; k < 4; ++k)
    if (std::abs(xyzw[k]) > std::abs(xyzw[largest])) largest = k;
  const bool negate = xyzw[largest] < 0;  // q and -q are the same rotation: make the largest positive
  uint32_t comp = uint32_t(largest);
  for (int k = 0; k < 4; ++k) {
    if (k == largest) continue;
    const uint32_t sign = uint32_t((xyzw[k] < 0) != negate);
    const uint32_t mag = std::min<uint32_t>(511, uint32_t(511.0f * (std::abs(xyzw[k]) / kSqrtHalf) + 0.5f));
    comp = (comp << 10) | (sign << 9) | mag;
  }
  return comp;
}

void unpack_smallest_three(uint32_t comp, float xyzw[4]) {
  const int largest = int(comp >> 30);
  float sum = 0;
  for (int k = 3; k >= 0; --k) {
    if (k == largest) continue;
    const float mag = kSqrtHalf * float(comp & 511u) / 511.0f;
    xyzw[k] = (comp >> 9) & 1u ? -mag : mag;
    sum += xyzw[k] * xyzw[k];
    comp >>= 10;
  }
  xyzw[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
}

}  // namespace

std::vector<uint8_t> encode_spz(const GaussianPly& g, const std::string& name, uint32_t version) {
  check_encodable(g, name);
  if (version != 2 && version != 3) throw Error(name, "SPZ version " + std::to_string(version) + " cannot be written (2 or 3)");
  if (g.count > kMaxPoints) throw Error(name, "too many Gaussians for SPZ: " + std::to_string(g.count));
  // The most fractional bits (up to SPZ's usual 12) that keep every coordinate inside 24 signed bits.
  float max_abs = 0;
  for (float v : g.positions) max_abs = std::max(max_abs, std::abs(v));
  int frac = 12;
  while (frac > 0 && std::ldexp(double(max_abs), frac) >= double((1 << 23) - 1)) --frac;
  if (std::ldexp(double(max_abs), frac) >= double((1 << 23) - 1))
    throw Error(name, "a position coordinate (" + std::to_string(max_abs) + ") is beyond SPZ's 24-bit range");

  const size_t n = g.count, coeffs = sh_coeffs(g.sh_degree), rest = GaussianPly::rest_per_gaussian(g.sh_degree);
  std::vector<uint8_t> raw;
  raw.reserve(kHeaderBytes + payload_bytes(n, g.sh_degree, version));
  put_u32(raw, kMagic);
  put_u32(raw, version);
  put_u32(raw, uint32_t(n));
  raw.push_back(uint8_t(g.sh_degree));
  raw.push_back(uint8_t(frac));
  raw.push_back(0);  // flags: not trained with antialiasing, no extensions
  raw.push_back(0);
  for (size_t i = 0; i < n * 3; ++i) {
    const int32_t fixed = int32_t(std::lround(std::ldexp(double(kFlipP[i % 3] * g.positions[i]), frac)));
    for (int b = 0; b < 3; ++b) raw.push_back(uint8_t(uint32_t(fixed) >> (8 * b)));
  }
  for (size_t i = 0; i < n; ++i) raw.push_back(to_byte(sigmoid(g.opacity[i]) * 255.0f));
  for (size_t i = 0; i < n * 3; ++i) raw.push_back(to_byte(g.f_dc[i] * (kColorScale * 255.0f) + 127.5f));
  for (size_t i = 0; i < n * 3; ++i) raw.push_back(to_byte((g.scales[i] + 10.0f) * 16.0f));
  for (size_t i = 0; i < n; ++i) {
    float q[4];
    unit_quaternion(g, i, q);  // w x y z
    float xyzw[4] = {q[1], -q[2], -q[3], q[0]};
    if (version >= 3) {
      put_u32(raw, pack_smallest_three(xyzw));
    } else {
      const float s = xyzw[3] < 0 ? -127.5f : 127.5f;  // w >= 0, rebuilt by the reader
      for (int k = 0; k < 3; ++k) raw.push_back(to_byte(xyzw[k] * s + 127.5f));
    }
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < coeffs; ++k)
      for (size_t c = 0; c < 3; ++c)
        raw.push_back(quantize_sh(kFlipSh[k] * g.f_rest[i * rest + c * coeffs + k], k < 3 ? 8 : 16));
  return gzip_compress(raw, name);
}

GaussianPly decode_spz(const uint8_t* data, size_t size, const std::string& name) {
  if (size < 2 || data[0] != 0x1f || data[1] != 0x8b) {
    if (size >= 4 && get_u32(data) == kMagic)
      throw Error(name, "SPZ version 4 or later (zstd-compressed) is not supported; versions 2 and 3 are");
    throw Error(name, "not an SPZ file (no gzip header)");
  }
  // The header comes first; the size it implies bounds the rest of the decompression.
  const size_t max_bytes = kHeaderBytes + payload_bytes(kMaxPoints, 3, 3);
  const std::vector<uint8_t> raw = gzip_decompress(data, size, max_bytes, name);
  if (raw.size() < kHeaderBytes)
    throw Error(name, "truncated: " + std::to_string(raw.size()) + " bytes after decompression, less than the 16-byte SPZ header");
  if (get_u32(raw.data()) != kMagic) throw Error(name, "not an SPZ file (bad magic number after decompression)");
  const uint32_t version = get_u32(raw.data() + 4);
  if (version != 2 && version != 3)
    throw Error(name, "SPZ version " + std::to_string(version) + " is not supported (2 and 3 are)");
  const uint32_t n = get_u32(raw.data() + 8);
  const int degree = raw[12];
  const int frac = raw[13];
  const uint8_t flags = raw[14];
  if (degree > 3) throw Error(name, "SPZ SH degree " + std::to_string(degree) + " is outside 0..3");
  if (frac > 24) throw Error(name, "SPZ fractional bits " + std::to_string(frac) + " are more than the 24 position bits");
  if (flags & kFlagExtensions) throw Error(name, "SPZ extensions (flag 0x2) are not supported");
  if (flags & ~(kFlagAntialiased | kFlagExtensions)) throw Error(name, "unknown SPZ flags " + std::to_string(flags));
  if (n > kMaxPoints) throw Error(name, "SPZ header claims " + std::to_string(n) + " Gaussians, more than supported");
  const size_t expected = kHeaderBytes + payload_bytes(n, degree, version);
  if (raw.size() != expected)
    throw Error(name, std::string(raw.size() < expected ? "truncated" : "corrupt") + ": " + std::to_string(raw.size()) +
                          " bytes after decompression, expected " + std::to_string(expected) + " for " +
                          std::to_string(n) + " Gaussians of SH degree " + std::to_string(degree) + " (SPZ version " +
                          std::to_string(version) + ")");

  GaussianPly g = sized_model(n, degree);
  const uint8_t* p = raw.data() + kHeaderBytes;
  const double unit = std::ldexp(1.0, -frac);
  for (size_t i = 0; i < size_t(n) * 3; ++i, p += 3) {
    int32_t fixed = int32_t(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16);
    if (fixed & 0x800000) fixed -= 0x1000000;  // sign of the 24-bit value
    g.positions[i] = kFlipP[i % 3] * float(double(fixed) * unit);
  }
  for (size_t i = 0; i < n; ++i) g.opacity[i] = logit_of_alpha(float(*p++) / 255.0f);
  for (size_t i = 0; i < size_t(n) * 3; ++i) g.f_dc[i] = (float(*p++) / 255.0f - 0.5f) / kColorScale;
  for (size_t i = 0; i < size_t(n) * 3; ++i) g.scales[i] = float(*p++) / 16.0f - 10.0f;
  for (size_t i = 0; i < n; ++i) {
    float xyzw[4];
    if (version >= 3) {
      unpack_smallest_three(get_u32(p), xyzw);
      p += 4;
    } else {
      float s2 = 0;
      for (int k = 0; k < 3; ++k) {
        xyzw[k] = float(*p++) / 127.5f - 1.0f;
        s2 += xyzw[k] * xyzw[k];
      }
      xyzw[3] = std::sqrt(std::max(0.0f, 1.0f - s2));
    }
    float* r = &g.rotations[i * 4];
    r[0] = xyzw[3], r[1] = xyzw[0], r[2] = -xyzw[1], r[3] = -xyzw[2];
  }
  const size_t coeffs = sh_coeffs(degree), rest = GaussianPly::rest_per_gaussian(degree);
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < coeffs; ++k)
      for (size_t c = 0; c < 3; ++c) g.f_rest[i * rest + c * coeffs + k] = kFlipSh[k] * (float(*p++) - 128.0f) / 128.0f;
  return g;
}

}  // namespace goris
