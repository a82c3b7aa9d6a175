// PlayCanvas compressed PLY (core/io/splat_formats.h has the layout and quantization): chunks of 256
// Gaussians in Morton order, each with its own value ranges, and 32 bits per attribute within them.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/io/ply_header.h"
#include "core/io/splat_codec.h"
#include "core/io/splat_formats.h"

namespace goris {
namespace {
using namespace splat_detail;
using ply_detail::PlyElement;
using ply_detail::PlyType;

constexpr size_t kChunk = 256;
constexpr const char* kChunkProps[18] = {"min_x",       "min_y",       "min_z",       "max_x",       "max_y",
                                         "max_z",       "min_scale_x", "min_scale_y", "min_scale_z", "max_scale_x",
                                         "max_scale_y", "max_scale_z", "min_r",       "min_g",       "min_b",
                                         "max_r",       "max_g",       "max_b"};
constexpr const char* kVertexProps[4] = {"packed_position", "packed_rotation", "packed_scale", "packed_color"};

// x in [lo, hi] as 0..1; a range narrower than 1e-5 encodes everything as 0 (decoded as lo).
float normalize(float x, float lo, float hi) {
  if (x <= lo) return 0.0f;
  if (x >= hi) return 1.0f;
  return hi - lo < 1e-5f ? 0.0f : (x - lo) / (hi - lo);
}
uint32_t unorm(float v, int bits) {
  const float top = float((1u << bits) - 1);
  return uint32_t(std::clamp(std::floor(v * top + 0.5f), 0.0f, top));
}
float from_unorm(uint32_t v, int bits) {
  const uint32_t top = (1u << bits) - 1;
  return float(v & top) / float(top);
}
uint32_t pack_11_10_11(float x, float y, float z) { return unorm(x, 11) << 21 | unorm(y, 10) << 11 | unorm(z, 11); }

// rot_0..3 normalised; the largest made positive; 2 bits for its index, 10 bits for each other.
uint32_t pack_rotation(const float q[4]) {
  int largest = 0;
  for (int k = 1; k < 4; ++k)
    if (std::abs(q[k]) > std::abs(q[largest])) largest = k;
  const float s = q[largest] < 0 ? -1.0f : 1.0f;
  uint32_t r = uint32_t(largest);
  for (int k = 0; k < 4; ++k)
    if (k != largest) r = (r << 10) | unorm(s * q[k] * kSqrtHalf + 0.5f, 10);
  return r;
}

void unpack_rotation(uint32_t v, float q[4]) {
  const float a = (from_unorm(v >> 20, 10) - 0.5f) / kSqrtHalf;
  const float b = (from_unorm(v >> 10, 10) - 0.5f) / kSqrtHalf;
  const float c = (from_unorm(v, 10) - 0.5f) / kSqrtHalf;
  const float m = std::sqrt(std::max(0.0f, 1.0f - (a * a + b * b + c * c)));
  const int largest = int(v >> 30);
  const float others[3] = {a, b, c};
  for (int k = 0, j = 0; k < 4; ++k) q[k] = k == largest ? m : others[j++];
}

// trunc((x / 8 + 0.5) * 256) in 0..255, and back to the middle of its step (the ends exactly at -4 and 4).
uint8_t quantize_sh(float x) { return uint8_t(std::clamp(std::trunc((x / 8.0f + 0.5f) * 256.0f), 0.0f, 255.0f)); }
float unquantize_sh(uint8_t v) {
  const float t = v == 0 ? 0.0f : v == 255 ? 1.0f : (float(v) + 0.5f) / 256.0f;
  return (t - 0.5f) * 8.0f;
}

struct MinMax {
  float lo = INFINITY, hi = -INFINITY;
  void add(float v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// Where each named property of an element lives: byte offset within an item and type.
struct Column {
  size_t offset = 0;
  PlyType type = PlyType::f32;
  bool found = false;
};
Column column(const PlyElement& e, const std::string& prop) {
  Column c;
  size_t at = 0;
  for (const auto& p : e.properties) {
    if (p.name == prop) {
      c = {at, p.type, true};
      break;
    }
    at += ply_detail::type_size(p.type);
  }
  return c;
}

}  // namespace

std::vector<uint32_t> compressed_ply_order(const GaussianPly& g) {
  // Morton (Z-order) code of each position quantized to 10 bits per axis inside the bounding box; a stable
  // sort keeps the original order among equal codes.
  MinMax box[3];
  for (size_t i = 0; i < g.count; ++i)
    for (int a = 0; a < 3; ++a) box[a].add(g.positions[i * 3 + a]);
  auto spread = [](uint32_t v) {  // 10 bits to every third of 30
    v &= 0x3ff;
    v = (v | v << 16) & 0x030000ff;
    v = (v | v << 8) & 0x0300f00f;
    v = (v | v << 4) & 0x030c30c3;
    v = (v | v << 2) & 0x09249249;
    return v;
  };
  std::vector<uint32_t> code(g.count);
  for (size_t i = 0; i < g.count; ++i) {
    uint32_t q[3];
    for (int a = 0; a < 3; ++a) {
      const float ext = box[a].hi - box[a].lo;
      const float t = ext > 0 ? (g.positions[i * 3 + a] - box[a].lo) / ext : 0.0f;
      q[a] = uint32_t(std::clamp(t * 1023.0f, 0.0f, 1023.0f));
    }
    code[i] = spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2;
  }
  std::vector<uint32_t> order(g.count);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
  return order;
}

std::vector<uint8_t> encode_compressed_ply(const GaussianPly& g, const std::string& name) {
  check_encodable(g, name);
  if (g.count > 0xffffffffu) throw Error(name, "too many Gaussians for a compressed PLY");
  const size_t n = g.count, chunks = (n + kChunk - 1) / kChunk, rest = GaussianPly::rest_per_gaussian(g.sh_degree);
  std::string h = "ply\nformat binary_little_endian 1.0\ncomment Generated by GOR-IS Studio\nelement chunk " +
                  std::to_string(chunks) + "\n";
  for (const char* p : kChunkProps) h.append("property float ").append(p).append("\n");
  h += "element vertex " + std::to_string(n) + "\n";
  for (const char* p : kVertexProps) h.append("property uint ").append(p).append("\n");
  if (rest > 0) {
    h += "element sh " + std::to_string(n) + "\n";
    for (size_t k = 0; k < rest; ++k) h += "property uchar f_rest_" + std::to_string(k) + "\n";
  }
  h += "end_header\n";

  const std::vector<uint32_t> order = compressed_ply_order(g);
  std::vector<uint8_t> chunk_bytes, vertex_bytes, sh_bytes;
  chunk_bytes.reserve(chunks * 18 * 4);
  vertex_bytes.reserve(n * 16);
  sh_bytes.reserve(n * rest);
  for (size_t c = 0; c < chunks; ++c) {
    const size_t first = c * kChunk, last = std::min(n, first + kChunk);
    MinMax pos[3], scale[3], color[3];
    for (size_t j = first; j < last; ++j) {
      const size_t i = order[j];
      for (int a = 0; a < 3; ++a) {
        pos[a].add(g.positions[i * 3 + a]);
        scale[a].add(std::clamp(g.scales[i * 3 + a], -20.0f, 20.0f));
        color[a].add(g.f_dc[i * 3 + a] * kShC0 + 0.5f);
      }
    }
    for (const MinMax* m : {pos, scale, color}) {
      for (int a = 0; a < 3; ++a) put_f32(chunk_bytes, m[a].lo);
      for (int a = 0; a < 3; ++a) put_f32(chunk_bytes, m[a].hi);
    }
    for (size_t j = first; j < last; ++j) {
      const size_t i = order[j];
      const float* p = &g.positions[i * 3];
      const float* s = &g.scales[i * 3];
      put_u32(vertex_bytes, pack_11_10_11(normalize(p[0], pos[0].lo, pos[0].hi), normalize(p[1], pos[1].lo, pos[1].hi),
                                          normalize(p[2], pos[2].lo, pos[2].hi)));
      float q[4];
      unit_quaternion(g, i, q);
      put_u32(vertex_bytes, pack_rotation(q));
      put_u32(vertex_bytes, pack_11_10_11(normalize(s[0], scale[0].lo, scale[0].hi), normalize(s[1], scale[1].lo, scale[1].hi),
                                          normalize(s[2], scale[2].lo, scale[2].hi)));
      uint32_t rgba = 0;
      for (int a = 0; a < 3; ++a)
        rgba |= unorm(normalize(g.f_dc[i * 3 + a] * kShC0 + 0.5f, color[a].lo, color[a].hi), 8) << (24 - 8 * a);
      rgba |= unorm(sigmoid(g.opacity[i]), 8);
      put_u32(vertex_bytes, rgba);
      for (size_t k = 0; k < rest; ++k) sh_bytes.push_back(quantize_sh(g.f_rest[i * rest + k]));
    }
  }
  std::vector<uint8_t> out(h.begin(), h.end());
  out.insert(out.end(), chunk_bytes.begin(), chunk_bytes.end());
  out.insert(out.end(), vertex_bytes.begin(), vertex_bytes.end());
  out.insert(out.end(), sh_bytes.begin(), sh_bytes.end());
  return out;
}

GaussianPly decode_compressed_ply(const uint8_t* data, size_t size, const std::string& name) {
  const ply_detail::PlyHeader h = ply_detail::parse_header(data, size, name);
  if (h.format != ply_detail::PlyFormat::binary_little_endian)
    throw Error(name, "a compressed PLY must be binary_little_endian");
  const PlyElement *chunk = nullptr, *vertex = nullptr, *sh = nullptr;
  std::vector<size_t> offsets;  // each element's first byte
  size_t at = h.data_offset;
  for (const PlyElement& e : h.elements) {
    if (e.name == "chunk") chunk = &e;
    else if (e.name == "vertex") vertex = &e;
    else if (e.name == "sh") sh = &e;
    else throw Error(name, "compressed PLY: unexpected element '" + e.name + "'");
    if (e.has_list()) throw Error(name, "compressed PLY: element '" + e.name + "' has a list property");
    const size_t stride = e.binary_stride();
    offsets.push_back(at);
    if (stride > 0 && e.count > (size - std::min(size, at)) / stride)
      throw Error(name, "truncated: element '" + e.name + "' needs " + std::to_string(e.count) + " x " +
                            std::to_string(stride) + " bytes, the file has " + std::to_string(size - std::min(size, at)) +
                            " left");
    at += size_t(e.count) * stride;
  }
  if (!chunk || !vertex) throw Error(name, "compressed PLY: the elements 'chunk' and 'vertex' are required");
  auto offset_of = [&](const PlyElement* e) { return offsets[size_t(e - h.elements.data())]; };

  const size_t n = size_t(vertex->count);
  if (chunk->count != (n + kChunk - 1) / kChunk)
    throw Error(name, "compressed PLY: " + std::to_string(chunk->count) + " chunks for " + std::to_string(n) +
                          " Gaussians, expected " + std::to_string((n + kChunk - 1) / kChunk) + " (256 per chunk)");
  std::array<Column, 18> cc;
  for (size_t k = 0; k < 18; ++k) {
    cc[k] = column(*chunk, kChunkProps[k]);
    if (k < 12 && (!cc[k].found || cc[k].type != PlyType::f32))
      throw Error(name, std::string("compressed PLY: chunk property '") + kChunkProps[k] + "' (float) is missing");
  }
  const bool chunk_colors = cc[12].found;
  for (size_t k = 12; k < 18; ++k)
    if (cc[k].found != chunk_colors || (cc[k].found && cc[k].type != PlyType::f32))
      throw Error(name, "compressed PLY: the chunk colour ranges min_r..max_b must be all present as floats, or none");
  std::array<Column, 4> vc;
  for (size_t k = 0; k < 4; ++k) {
    vc[k] = column(*vertex, kVertexProps[k]);
    if (!vc[k].found || vc[k].type != PlyType::u32)
      throw Error(name, std::string("compressed PLY: vertex property '") + kVertexProps[k] + "' (uint) is missing");
  }
  int degree = 0;
  std::vector<Column> sc;
  if (sh) {
    const size_t m = sh->properties.size();
    degree = m == 9 ? 1 : m == 24 ? 2 : m == 45 ? 3 : -1;
    if (degree < 0) throw Error(name, "compressed PLY: element 'sh' has " + std::to_string(m) + " properties, expected 9, 24 or 45");
    if (sh->count != vertex->count)
      throw Error(name, "compressed PLY: element 'sh' has " + std::to_string(sh->count) + " items for " +
                            std::to_string(n) + " Gaussians");
    for (size_t k = 0; k < m; ++k) {
      sc.push_back(column(*sh, "f_rest_" + std::to_string(k)));
      if (!sc.back().found || sc.back().type != PlyType::u8)
        throw Error(name, "compressed PLY: sh property 'f_rest_" + std::to_string(k) + "' (uchar) is missing");
    }
  }

  GaussianPly g = sized_model(n, degree);
  const size_t cstride = chunk->binary_stride(), vstride = vertex->binary_stride();
  const uint8_t* cbase = data + offset_of(chunk);
  const uint8_t* vbase = data + offset_of(vertex);
  for (size_t c = 0; c < chunk->count; ++c)
    for (size_t k = 0; k < (chunk_colors ? 18u : 12u); ++k)
      if (!std::isfinite(get_f32(cbase + c * cstride + cc[k].offset)))
        throw Error(name, std::string("compressed PLY: chunk ") + std::to_string(c) + " property '" + kChunkProps[k] +
                              "' is not a finite number");
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* cr = cbase + (i / kChunk) * cstride;
    const uint8_t* vr = vbase + i * vstride;
    auto ch = [&](size_t k) { return get_f32(cr + cc[k].offset); };
    auto lerp = [](float a, float b, float t) { return a * (1.0f - t) + b * t; };
    const uint32_t pp = get_u32(vr + vc[0].offset), pr = get_u32(vr + vc[1].offset), ps = get_u32(vr + vc[2].offset),
                   pc = get_u32(vr + vc[3].offset);
    const float pt[3] = {from_unorm(pp >> 21, 11), from_unorm(pp >> 11, 10), from_unorm(pp, 11)};
    const float st[3] = {from_unorm(ps >> 21, 11), from_unorm(ps >> 11, 10), from_unorm(ps, 11)};
    for (int a = 0; a < 3; ++a) {
      g.positions[i * 3 + a] = lerp(ch(size_t(a)), ch(size_t(3 + a)), pt[a]);
      g.scales[i * 3 + a] = lerp(ch(size_t(6 + a)), ch(size_t(9 + a)), st[a]);
      const float t = from_unorm(pc >> (24 - 8 * a), 8);
      const float col = chunk_colors ? lerp(ch(size_t(12 + a)), ch(size_t(15 + a)), t) : t;
      g.f_dc[i * 3 + a] = (col - 0.5f) / kShC0;
    }
    g.opacity[i] = logit_of_alpha(from_unorm(pc, 8));
    unpack_rotation(pr, &g.rotations[i * 4]);
  }
  if (sh) {
    const size_t sstride = sh->binary_stride(), rest = sc.size();
    const uint8_t* sbase = data + offset_of(sh);
    for (size_t i = 0; i < n; ++i)
      for (size_t k = 0; k < rest; ++k) g.f_rest[i * rest + k] = unquantize_sh(sbase[i * sstride + sc[k].offset]);
  }
  check_decoded(g, name);
  return g;
}

}  // namespace goris
