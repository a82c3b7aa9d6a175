#include "core/io/npy.h"

#include <cctype>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>

#include "core/io/file_bytes.h"
#include "core/util/error.h"

namespace goris {
namespace {

// The header is a Python dict literal, e.g. {'descr': '<f8', 'fortran_order': False, 'shape': (119, 17), }
struct NpyHeader {
  std::optional<std::string> descr;
  std::optional<bool> fortran_order;
  std::optional<std::vector<size_t>> shape;
};

class HeaderParser {
 public:
  HeaderParser(std::string_view text, const std::string& name) : s_(text), name_(name) {}

  NpyHeader parse() {
    NpyHeader h;
    skip_space();
    expect('{');
    while (true) {
      skip_space();
      if (peek() == '}') break;
      const std::string key = parse_string();
      skip_space();
      expect(':');
      skip_space();
      if (key == "descr") {
        h.descr = parse_string();
      } else if (key == "fortran_order") {
        h.fortran_order = parse_bool();
      } else if (key == "shape") {
        h.shape = parse_shape();
      } else {
        fail("unexpected key '" + key + "'");
      }
      skip_space();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() != '}') fail("expected ',' or '}'");
    }
    ++pos_;
    return h;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(name_, "malformed .npy header at character " + std::to_string(pos_) + ": " + what);
  }
  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  std::string parse_string() {
    const char q = peek();
    if (q != '\'' && q != '"') fail("expected a quoted string");
    ++pos_;
    const size_t start = pos_;
    while (pos_ < s_.size() && s_[pos_] != q) ++pos_;
    if (pos_ >= s_.size()) fail("unterminated string");
    return std::string(s_.substr(start, pos_++ - start));
  }
  bool parse_bool() {
    if (s_.substr(pos_, 4) == "True") {
      pos_ += 4;
      return true;
    }
    if (s_.substr(pos_, 5) == "False") {
      pos_ += 5;
      return false;
    }
    fail("expected True or False");
  }
  std::vector<size_t> parse_shape() {
    std::vector<size_t> shape;
    expect('(');
    while (true) {
      skip_space();
      if (peek() == ')') break;
      if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected a dimension");
      size_t v = 0;
      while (std::isdigit(static_cast<unsigned char>(peek()))) {
        const size_t d = size_t(s_[pos_++] - '0');
        if (v > (std::numeric_limits<size_t>::max() - d) / 10) fail("dimension too large");
        v = v * 10 + d;
      }
      // Python writes a trailing "L" for longs in very old files.
      if (peek() == 'L') ++pos_;
      shape.push_back(v);
      skip_space();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() != ')') fail("expected ',' or ')' in shape");
    }
    ++pos_;
    return shape;
  }

  std::string_view s_;
  const std::string& name_;
  size_t pos_ = 0;
};

enum class Kind { Float, Int, UInt, Bool };
struct DType {
  Kind kind;
  size_t size;
};

DType parse_descr(const std::string& d, const std::string& name) {
  if (d.size() < 3) throw Error(name, "unsupported .npy dtype '" + d + "'");
  const char order = d[0];
  const std::string code = d.substr(1);
  DType t{};
  if (code == "f4") t = {Kind::Float, 4};
  else if (code == "f8") t = {Kind::Float, 8};
  else if (code == "i1") t = {Kind::Int, 1};
  else if (code == "i2") t = {Kind::Int, 2};
  else if (code == "i4") t = {Kind::Int, 4};
  else if (code == "i8") t = {Kind::Int, 8};
  else if (code == "u1") t = {Kind::UInt, 1};
  else if (code == "u2") t = {Kind::UInt, 2};
  else if (code == "u4") t = {Kind::UInt, 4};
  else if (code == "u8") t = {Kind::UInt, 8};
  else if (code == "b1") t = {Kind::Bool, 1};
  else
    throw Error(name, "unsupported .npy dtype '" + d +
                          "' (supported: f4 f8 i1 i2 i4 i8 u1 u2 u4 u8 b1, little-endian)");
  if (order == '>' && t.size > 1) throw Error(name, "big-endian .npy data ('" + d + "') is not supported");
  if (order != '<' && order != '|' && order != '>' && order != '=')
    throw Error(name, "unsupported .npy byte order in dtype '" + d + "'");
  return t;
}

// Little-endian loads; the host is little-endian (x86-64, aarch64).
template <class T>
T load_le(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

double convert(const uint8_t* p, DType t) {
  switch (t.kind) {
    case Kind::Float: return t.size == 4 ? double(load_le<float>(p)) : load_le<double>(p);
    case Kind::Bool: return p[0] != 0 ? 1.0 : 0.0;
    case Kind::Int:
      switch (t.size) {
        case 1: return double(load_le<int8_t>(p));
        case 2: return double(load_le<int16_t>(p));
        case 4: return double(load_le<int32_t>(p));
        default: return double(load_le<int64_t>(p));
      }
    case Kind::UInt:
      switch (t.size) {
        case 1: return double(p[0]);
        case 2: return double(load_le<uint16_t>(p));
        case 4: return double(load_le<uint32_t>(p));
        default: return double(load_le<uint64_t>(p));
      }
  }
  return 0;
}

}  // namespace

NpyArray parse_npy(const uint8_t* bytes, size_t n, const std::string& name) {
  static const uint8_t kMagic[6] = {0x93, 'N', 'U', 'M', 'P', 'Y'};
  if (n < 10 || std::memcmp(bytes, kMagic, 6) != 0) throw Error(name, "not a .npy file (bad magic bytes)");
  const int major = bytes[6];
  size_t header_len = 0, offset = 0;
  if (major == 1) {
    header_len = load_le<uint16_t>(bytes + 8);
    offset = 10;
  } else if (major == 2 || major == 3) {
    if (n < 12) throw Error(name, "truncated .npy preamble");
    header_len = load_le<uint32_t>(bytes + 8);
    offset = 12;
  } else {
    throw Error(name, "unsupported .npy format version " + std::to_string(major));
  }
  if (header_len > n - offset)
    throw Error(name, "truncated .npy header: needs " + std::to_string(header_len) + " bytes, file has " +
                          std::to_string(n - offset) + " after the preamble");
  const std::string_view header(reinterpret_cast<const char*>(bytes + offset), header_len);
  const NpyHeader h = HeaderParser(header, name).parse();
  if (!h.descr) throw Error(name, "malformed .npy header: no 'descr'");
  if (!h.fortran_order) throw Error(name, "malformed .npy header: no 'fortran_order'");
  if (!h.shape) throw Error(name, "malformed .npy header: no 'shape'");
  if (*h.fortran_order) throw Error(name, "Fortran-order .npy arrays are not supported (save it in C order)");
  const DType t = parse_descr(*h.descr, name);

  size_t count = 1;
  for (size_t d : *h.shape) {
    if (d != 0 && count > std::numeric_limits<size_t>::max() / d) throw Error(name, ".npy shape is too large");
    count *= d;
  }
  const size_t data_start = offset + header_len;
  const size_t available = n - data_start;
  if (count > available / t.size)
    throw Error(name, "truncated .npy data: shape needs " + std::to_string(count) + " values of " +
                          std::to_string(t.size) + " bytes, the file has " + std::to_string(available) +
                          " bytes of data");
  if (count * t.size != available)
    throw Error(name, ".npy data size does not match its shape: " + std::to_string(available - count * t.size) +
                          " extra bytes after the data");

  NpyArray a;
  a.shape = *h.shape;
  a.data.resize(count);
  const uint8_t* p = bytes + data_start;
  for (size_t i = 0; i < count; ++i) a.data[i] = convert(p + i * t.size, t);
  return a;
}

NpyArray load_npy(const std::filesystem::path& path) {
  const auto bytes = read_file_bytes(path);
  return parse_npy(bytes.data(), bytes.size(), path.string());
}

}  // namespace goris
