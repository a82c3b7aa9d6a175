// The antimatter15 .splat layout of web viewers (core/io/splat_formats.h has the layout): 32 bytes per
// Gaussian, no header, no SH above degree 0.
#include <cmath>

#include "core/io/splat_codec.h"
#include "core/io/splat_formats.h"

namespace goris {
using namespace splat_detail;

namespace {
constexpr size_t kBytes = 32;
}

std::vector<uint8_t> encode_antimatter_splat(const GaussianPly& g, const std::string& name) {
  check_encodable(g, name);
  if (g.count == 0) throw Error(name, "a .splat file cannot hold an empty model (it has no header)");
  std::vector<uint8_t> out;
  out.reserve(g.count * kBytes);
  for (size_t i = 0; i < g.count; ++i) {
    for (int a = 0; a < 3; ++a) put_f32(out, g.positions[i * 3 + a]);
    for (int a = 0; a < 3; ++a) {
      const float s = std::exp(g.scales[i * 3 + a]);
      if (!std::isfinite(s) || !(s > 0))
        throw Error(name, "cannot encode: the scale of Gaussian " + std::to_string(i) + " overflows a float (log scale " +
                              std::to_string(g.scales[i * 3 + a]) + ")");
      put_f32(out, s);
    }
    for (int a = 0; a < 3; ++a) out.push_back(to_byte((g.f_dc[i * 3 + a] * kShC0 + 0.5f) * 255.0f));
    out.push_back(to_byte(sigmoid(g.opacity[i]) * 255.0f));
    float q[4];
    unit_quaternion(g, i, q);
    for (int k = 0; k < 4; ++k) out.push_back(to_byte(q[k] * 128.0f + 128.0f));
  }
  return out;
}

GaussianPly decode_antimatter_splat(const uint8_t* data, size_t size, const std::string& name) {
  if (size == 0) throw Error(name, "empty file (a .splat file holds 32 bytes per Gaussian)");
  if (size % kBytes != 0)
    throw Error(name, "truncated or corrupt: " + std::to_string(size) + " bytes is not a multiple of 32 (bytes per Gaussian in a .splat file)");
  const size_t n = size / kBytes;
  GaussianPly g = sized_model(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = data + i * kBytes;
    for (int a = 0; a < 3; ++a) {
      const float x = get_f32(p + 4 * a), s = get_f32(p + 12 + 4 * a);
      if (!std::isfinite(x)) throw Error(name, "Gaussian " + std::to_string(i) + ": position is not a finite number");
      if (!std::isfinite(s) || !(s > 0))
        throw Error(name, "Gaussian " + std::to_string(i) + ": scale " + std::to_string(s) + " is not a positive finite number");
      g.positions[i * 3 + a] = x;
      g.scales[i * 3 + a] = std::log(s);
      g.f_dc[i * 3 + a] = (float(p[24 + a]) / 255.0f - 0.5f) / kShC0;
    }
    g.opacity[i] = logit_of_alpha(float(p[27]) / 255.0f);
    float q[4], n2 = 0;
    for (int k = 0; k < 4; ++k) {
      q[k] = (float(p[28 + k]) - 128.0f) / 128.0f;
      n2 += q[k] * q[k];
    }
    const float inv = n2 > 0 ? 1.0f / std::sqrt(n2) : 0.0f;
    float* r = &g.rotations[i * 4];
    if (n2 > 0)
      for (int k = 0; k < 4; ++k) r[k] = q[k] * inv;
    else
      r[0] = 1, r[1] = r[2] = r[3] = 0;
  }
  return g;
}

}  // namespace goris
