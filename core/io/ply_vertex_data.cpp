// Converting the data section of a PLY file: element skipping, ASCII words, and the vertex columns, which
// are filled in blocks of rows, one property at a time, with the type switch outside the row loop.
#include "core/io/ply_vertex_data.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "core/util/error.h"

namespace goris::ply_detail {
namespace {

// double -> float without the undefined behaviour of converting out-of-range values: those become
// infinite, which the caller reports as not finite.
float to_float(double d) {
  return std::fabs(d) <= double(std::numeric_limits<float>::max()) ? float(d)
                                                                    : std::numeric_limits<float>::infinity();
}

// --- skipping elements that come before the vertex element -------------------------------------------

template <typename T>
uint64_t load_count(const uint8_t* p, bool& negative) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  negative = v < 0;
  return negative ? 0 : uint64_t(v);
}

uint64_t read_list_length(PlyType t, const uint8_t* p, bool& negative) {
  switch (t) {
    case PlyType::i8: return load_count<int8_t>(p, negative);
    case PlyType::u8: return load_count<uint8_t>(p, negative);
    case PlyType::i16: return load_count<int16_t>(p, negative);
    case PlyType::u16: return load_count<uint16_t>(p, negative);
    case PlyType::i32: return load_count<int32_t>(p, negative);
    case PlyType::u32: return load_count<uint32_t>(p, negative);
    default: negative = false; return 0;  // the header accepts only integer count types
  }
}

// --- ASCII tokens ---------------------------------------------------------------------------------------

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

std::string shown(std::string_view tok) {
  std::string s;
  for (size_t i = 0; i < tok.size() && i < 40; ++i) s += (tok[i] >= 32 && tok[i] < 127) ? tok[i] : '?';
  return "'" + s + (tok.size() > 40 ? "...'" : "'");
}

template <typename T>
bool parse_whole(std::string_view tok, T& v) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b < e && *b == '+' && e - b > 1 && b[1] != '-' && b[1] != '+') ++b;  // from_chars rejects '+'
  const auto r = std::from_chars(b, e, v);
  return r.ec == std::errc() && r.ptr == e;
}

// One ASCII value of type t as a float; false when the word is not a number of that type.
bool ascii_value(std::string_view tok, PlyType t, float& out) {
  switch (t) {
    case PlyType::f32: return parse_whole(tok, out);
    case PlyType::f64: {
      double d;
      if (!parse_whole(tok, d)) return false;
      out = to_float(d);
      return true;
    }
    default: {
      int64_t i;
      if (!parse_whole(tok, i)) return false;
      int64_t lo = 0, hi = 0;
      switch (t) {
        case PlyType::i8: lo = INT8_MIN, hi = INT8_MAX; break;
        case PlyType::u8: hi = UINT8_MAX; break;
        case PlyType::i16: lo = INT16_MIN, hi = INT16_MAX; break;
        case PlyType::u16: hi = UINT16_MAX; break;
        case PlyType::i32: lo = INT32_MIN, hi = INT32_MAX; break;
        default: hi = UINT32_MAX; break;
      }
      if (i < lo || i > hi) return false;
      out = float(i);
      return true;
    }
  }
}

// --- the vertex element -----------------------------------------------------------------------------

// Column::saturate: an infinite v becomes +-limit (true); NaN, or no limit, stays an error (false).
bool saturated(float& v, float limit) {
  if (!(limit > 0.0f) || !std::isinf(v)) return false;
  v = v > 0.0f ? limit : -limit;
  return true;
}

Error non_finite(const std::string& name, size_t vertex, const PlyProperty& p) {
  return Error(name, "vertex " + std::to_string(vertex) + ": property '" + p.name +
                         "' is not a finite float (NaN, infinite or out of float range)");
}

// Converts rows [r0, r1) of one column; the type is fixed for the whole loop.
template <typename T>
void convert_column(const uint8_t* rows, size_t row_bytes, size_t r0, size_t r1, const Column& c,
                    const std::string& name) {
  // Locals, so that the stores cannot alias the column description and the loop stays tight.
  const uint8_t* src = rows + r0 * row_bytes + c.byte_offset;
  float* const dst0 = c.dst + r0 * c.stride + c.offset;
  const size_t step = c.stride;
  float* dst = dst0;
  bool finite = true;
  for (size_t r = r0; r < r1; ++r, src += row_bytes, dst += step) {
    T v;
    std::memcpy(&v, src, sizeof(T));
    float f;
    if constexpr (std::is_same_v<T, double>) f = to_float(v);
    else f = static_cast<float>(v);
    if constexpr (std::is_floating_point_v<T>) finite &= std::isfinite(f);
    *dst = f;
  }
  if (!finite)
    for (size_t r = r0; r < r1; ++r) {
      float& v = dst0[(r - r0) * step];
      if (!std::isfinite(v) && !saturated(v, c.saturate)) throw non_finite(name, r, *c.prop);
    }
}

}  // namespace

size_t skip_binary_element(const PlyElement& e, const uint8_t* data, size_t size, size_t pos,
                           const std::string& name) {
  auto truncated = [&]() {
    return Error(name, "truncated: element '" + e.name + "' (" + std::to_string(e.count) +
                           " items, before the vertex element) runs past the end of the file (" +
                           std::to_string(size) + " bytes)");
  };
  if (!e.has_list()) {
    const size_t stride = e.binary_stride();
    if (stride != 0 && e.count > (size - pos) / stride) throw truncated();
    return pos + size_t(e.count) * stride;
  }
  // Every item holds at least one list length, so this loop ends within `size` bytes.
  for (uint64_t i = 0; i < e.count; ++i)
    for (const PlyProperty& p : e.properties) {
      if (!p.is_list) {
        if (size - pos < type_size(p.type)) throw truncated();
        pos += type_size(p.type);
        continue;
      }
      if (size - pos < type_size(p.count_type)) throw truncated();
      bool negative = false;
      const uint64_t n = read_list_length(p.count_type, data + pos, negative);
      if (negative)
        throw Error(name, "element '" + e.name + "' item " + std::to_string(i) + ": list '" + p.name +
                              "' has a negative length");
      pos += type_size(p.count_type);
      if (n > (size - pos) / type_size(p.type)) throw truncated();
      pos += size_t(n) * type_size(p.type);
    }
  return pos;
}

void skip_ascii_element(const PlyElement& e, AsciiTokens& tok, const std::string& name) {
  if (e.properties.empty()) return;
  auto truncated = [&](uint64_t i) {
    return Error(name, "truncated: the data ends in item " + std::to_string(i) + " of element '" + e.name +
                           "' (before the vertex element)");
  };
  for (uint64_t i = 0; i < e.count; ++i)  // each item consumes at least one word
    for (const PlyProperty& p : e.properties) {
      std::string_view w = tok.next();
      if (w.empty()) throw truncated(i);
      if (!p.is_list) continue;
      uint64_t n = 0;
      if (!parse_whole(w, n))
        throw Error(name, "element '" + e.name + "' item " + std::to_string(i) + ": invalid list length " + shown(w));
      for (uint64_t k = 0; k < n; ++k)
        if (tok.next().empty()) throw truncated(i);
    }
}

void read_binary_vertices(const uint8_t* rows, size_t count, size_t row_bytes, const std::vector<Column>& cols,
                          const std::string& name) {
  // Tasks of 4096 rows; within a task, tiles small enough for the rows to stay in L1 while every column
  // passes over them.
  const size_t tile = std::max<size_t>(8, 16384 / std::max<size_t>(row_bytes, 1));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& b) {
    for (size_t t0 = b.begin(); t0 < b.end(); t0 += tile) {
      const size_t t1 = std::min(b.end(), t0 + tile);
      for (const Column& c : cols) {
        switch (c.prop->type) {
          case PlyType::i8: convert_column<int8_t>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::u8: convert_column<uint8_t>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::i16: convert_column<int16_t>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::u16: convert_column<uint16_t>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::i32: convert_column<int32_t>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::u32: convert_column<uint32_t>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::f32: convert_column<float>(rows, row_bytes, t0, t1, c, name); break;
          case PlyType::f64: convert_column<double>(rows, row_bytes, t0, t1, c, name); break;
        }
      }
    }
  });
}

void read_ascii_vertices(AsciiTokens& tok, size_t count, const std::vector<Column>& cols, const std::string& name,
                         size_t data_bytes) {
  for (size_t i = 0; i < count; ++i)
    for (const Column& c : cols) {
      const std::string_view w = tok.next();
      if (w.empty())
        throw Error(name, "truncated: the header declares " + std::to_string(count) +
                              " vertices but the " + std::to_string(data_bytes) +
                              " bytes of data after the header end in vertex " + std::to_string(i) +
                              " (property '" + c.prop->name + "')");
      float f;
      if (!ascii_value(w, c.prop->type, f))
        throw Error(name, "vertex " + std::to_string(i) + ": property '" + c.prop->name + "' has invalid " +
                              type_name(c.prop->type) + " value " + shown(w));
      if (!std::isfinite(f) && !saturated(f, c.saturate)) throw non_finite(name, i, *c.prop);
      c.dst[i * c.stride + c.offset] = f;
    }
}

std::string_view AsciiTokens::next() {
  while (p < end && is_space(*p)) ++p;
  const char* b = p;
  while (p < end && !is_space(*p)) ++p;
  return std::string_view(b, size_t(p - b));
}

}  // namespace goris::ply_detail
