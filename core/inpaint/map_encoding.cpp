#include "core/inpaint/map_encoding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/util/error.h"

namespace goris {

namespace {

constexpr float kLow = 0.1f, kSpan = 0.8f;  // [lo, hi] -> [0.1, 0.9]

bool valid_depth(float z) { return std::isfinite(z) && z > 0.0f; }

// Widens a degenerate range so that its value encodes to 0.5.
void widen(float& lo, float& hi) {
  if (hi > lo) return;
  const float half = 0.5f * std::max(std::fabs(lo), 1e-6f);
  lo -= half;
  hi += half;
}

void check_channels(const Image& map, const MapInfo& info) {
  const int c = map.channels;
  const bool ok = info.kind == MapKind::Normal                                 ? c == 3
                  : info.kind == MapKind::Depth || info.kind == MapKind::Unit ? c == 1
                                                                               : c >= 1 && c <= 4;
  if (!ok)
    throw Error(map_label(info), std::string("a ") + map_kind_name(info.kind) + " map cannot have " +
                                     std::to_string(c) + " channel(s)");
}

}  // namespace

std::string map_label(const MapInfo& info) { return info.view + "/" + info.map; }

void save_encoded_png(const std::filesystem::path& path, const Image& encoded, MapKind kind) {
  const bool sixteen = kind == MapKind::Depth || kind == MapKind::Data;
  if (encoded.channels != 2) {
    save_png(path, encoded, sixteen);
    return;
  }
  Image rgb(encoded.width, encoded.height, 3, Device::CPU);
  const std::vector<float> v = encoded.pixels.to_host();
  for (std::size_t p = 0; p < encoded.pixel_count(); ++p) {
    rgb.pixels[p * 3 + 0] = v[p * 2 + 0];
    rgb.pixels[p * 3 + 1] = v[p * 2 + 1];
    rgb.pixels[p * 3 + 2] = 0.0f;
  }
  save_png(path, rgb, sixteen);
}

Image adapt_channels(const Image& got, const Image& encoded) {
  const int C = encoded.channels, G = got.channels;
  const std::vector<float> g = got.pixels.to_host(), e = encoded.pixels.to_host();
  Image out(got.width, got.height, C, Device::CPU);
  for (std::size_t p = 0; p < got.pixel_count(); ++p)
    for (int c = 0; c < C; ++c) {
      const float* px = &g[p * G];
      out.pixels[p * C + c] = C == 1 && G >= 3 ? (px[0] + px[1] + px[2]) / 3.0f
                              : G <= 2         ? px[0]  // grey (+ alpha)
                              : c < 3          ? px[c]
                                               : e[p * C + c];
    }
  return out;
}

const char* map_kind_name(MapKind kind) {
  switch (kind) {
    case MapKind::Color: return "colour";
    case MapKind::Unit: return "unit";
    case MapKind::Normal: return "normal";
    case MapKind::Depth: return "depth";
    case MapKind::Data: return "data";
  }
  return "?";
}

EncodedMap encode_map(const Image& map, const Mask& mask, const MapInfo& info) {
  if (map.width != mask.width || map.height != mask.height)
    throw Error(map_label(info), "map is " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                                     " but the inpainting mask is " + std::to_string(mask.width) + "x" +
                                     std::to_string(mask.height));
  if (map.width <= 0 || map.height <= 0) throw Error(map_label(info), "empty map");
  check_channels(map, info);
  const int C = map.channels;
  const std::size_t n = map.pixel_count();
  const std::vector<float> in = map.pixels.to_host();

  EncodedMap enc;
  enc.kind = info.kind;
  enc.hole = mask;
  enc.image = Image(map.width, map.height, C, Device::CPU);
  float* out = enc.image.pixels.data();

  if (info.kind != MapKind::Depth)
    for (std::size_t p = 0; p < n; ++p)
      if (!mask.data[p])
        for (int c = 0; c < C; ++c)
          if (!std::isfinite(in[p * C + c]))
            throw Error(map_label(info), "non-finite value outside the inpainting mask at pixel (" +
                                             std::to_string(p % map.width) + ", " + std::to_string(p / map.width) + ")");

  switch (info.kind) {
    case MapKind::Color:
    case MapKind::Unit:
      for (std::size_t i = 0; i < n * C; ++i) out[i] = std::isfinite(in[i]) ? in[i] : 0.0f;
      break;
    case MapKind::Normal:
      for (std::size_t p = 0; p < n; ++p) {
        const float* v = &in[p * 3];
        const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        const bool ok = std::isfinite(len) && len > 0.0f;
        for (int c = 0; c < 3; ++c) out[p * 3 + c] = ok ? v[c] / len * 0.5f + 0.5f : 0.5f;
      }
      break;
    case MapKind::Depth: {
      float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
      for (std::size_t p = 0; p < n; ++p)
        if (!mask.data[p] && valid_depth(in[p])) {
          lo = std::min(lo, 1.0f / in[p]);
          hi = std::max(hi, 1.0f / in[p]);
        }
      if (lo > hi) throw Error(map_label(info), "depth map has no valid depth (z > 0) outside the inpainting mask");
      widen(lo, hi);
      enc.lo = {lo};
      enc.hi = {hi};
      for (std::size_t p = 0; p < n; ++p) {
        if (valid_depth(in[p])) {
          out[p] = kLow + kSpan * (1.0f / in[p] - lo) / (hi - lo);
        } else {
          out[p] = 0.0f;
          enc.hole.data[p] = 255;  // "no surface" must not be a source of the fill
        }
      }
      break;
    }
    case MapKind::Data: {
      enc.lo.assign(C, std::numeric_limits<float>::max());
      enc.hi.assign(C, std::numeric_limits<float>::lowest());
      for (std::size_t p = 0; p < n; ++p)
        if (!mask.data[p])
          for (int c = 0; c < C; ++c) {
            enc.lo[c] = std::min(enc.lo[c], in[p * C + c]);
            enc.hi[c] = std::max(enc.hi[c], in[p * C + c]);
          }
      if (enc.lo[0] > enc.hi[0]) throw Error(map_label(info), "the inpainting mask covers the whole map");
      for (int c = 0; c < C; ++c) widen(enc.lo[c], enc.hi[c]);
      for (std::size_t p = 0; p < n; ++p)
        for (int c = 0; c < C; ++c) {
          const float v = in[p * C + c];
          out[p * C + c] = std::isfinite(v) ? kLow + kSpan * (v - enc.lo[c]) / (enc.hi[c] - enc.lo[c]) : 0.0f;
        }
      break;
    }
  }
  return enc;
}

Image decode_map(const Image& filled, const EncodedMap& enc) {
  const int C = filled.channels;
  const std::size_t n = filled.pixel_count();
  const std::vector<float> in = filled.pixels.to_host();
  Image dec(filled.width, filled.height, C, Device::CPU);
  float* out = dec.pixels.data();
  switch (enc.kind) {
    case MapKind::Color:
      for (std::size_t i = 0; i < n * C; ++i) out[i] = std::max(in[i], 0.0f);
      break;
    case MapKind::Unit:
      for (std::size_t i = 0; i < n * C; ++i) out[i] = std::clamp(in[i], 0.0f, 1.0f);
      break;
    case MapKind::Normal:
      for (std::size_t p = 0; p < n; ++p) {
        float v[3];
        for (int c = 0; c < 3; ++c) v[c] = 2.0f * in[p * 3 + c] - 1.0f;
        const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (std::isfinite(len) && len > 1e-6f) {
          for (int c = 0; c < 3; ++c) out[p * 3 + c] = v[c] / len;
        } else {
          out[p * 3 + 0] = 0.0f;
          out[p * 3 + 1] = 0.0f;
          out[p * 3 + 2] = -1.0f;
        }
      }
      break;
    case MapKind::Depth: {
      const float lo = enc.lo[0], hi = enc.hi[0];
      for (std::size_t p = 0; p < n; ++p) {
        const float inv = lo + (in[p] - kLow) / kSpan * (hi - lo);
        out[p] = std::isfinite(inv) && inv > 0.0f ? 1.0f / inv : 0.0f;
      }
      break;
    }
    case MapKind::Data:
      for (std::size_t p = 0; p < n; ++p)
        for (int c = 0; c < C; ++c)
          out[p * C + c] = enc.lo[c] + (in[p * C + c] - kLow) / kSpan * (enc.hi[c] - enc.lo[c]);
      break;
  }
  return dec;
}

}  // namespace goris
