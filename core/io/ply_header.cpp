#include "core/io/ply_header.h"

#include <charconv>
#include <string_view>

#include "core/util/error.h"

namespace goris::ply_detail {
namespace {

// Header text quoted in messages: printable, and short (the input may be any bytes).
std::string shown(std::string_view s) {
  std::string out = "'";
  for (size_t i = 0; i < s.size() && i < 60; ++i) out += (s[i] >= 32 && s[i] < 127) ? s[i] : '?';
  if (s.size() > 60) out += "...";
  return out + "'";
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

bool parse_type(std::string_view s, PlyType& t) {
  struct Name {
    const char* a;
    const char* b;
    PlyType t;
  };
  static const Name names[] = {{"char", "int8", PlyType::i8},       {"uchar", "uint8", PlyType::u8},
                               {"short", "int16", PlyType::i16},    {"ushort", "uint16", PlyType::u16},
                               {"int", "int32", PlyType::i32},      {"uint", "uint32", PlyType::u32},
                               {"float", "float32", PlyType::f32},  {"double", "float64", PlyType::f64}};
  for (const Name& n : names)
    if (s == n.a || s == n.b) {
      t = n.t;
      return true;
    }
  return false;
}

bool is_integer(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

}  // namespace

size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8: return 1;
    case PlyType::i16:
    case PlyType::u16: return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 0;
}

const char* type_name(PlyType t) {
  switch (t) {
    case PlyType::i8: return "char";
    case PlyType::u8: return "uchar";
    case PlyType::i16: return "short";
    case PlyType::u16: return "ushort";
    case PlyType::i32: return "int";
    case PlyType::u32: return "uint";
    case PlyType::f32: return "float";
    case PlyType::f64: return "double";
  }
  return "?";
}

bool PlyElement::has_list() const {
  for (const PlyProperty& p : properties)
    if (p.is_list) return true;
  return false;
}

size_t PlyElement::binary_stride() const {
  size_t s = 0;
  for (const PlyProperty& p : properties) s += type_size(p.type);
  return s;
}

PlyHeader parse_header(const uint8_t* data, size_t size, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  PlyHeader h;
  bool have_format = false, have_end = false;
  size_t pos = 0;
  int line_no = 0;
  auto fail = [&](const std::string& problem) -> Error {
    return Error(name, "PLY header line " + std::to_string(line_no) + ": " + problem);
  };

  while (!have_end) {
    const size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) {
      if (line_no == 0 && size == 0) throw Error(name, "empty file, not a PLY file");
      throw Error(name, line_no == 0 ? "not a PLY file (no complete first line)"
                                     : "PLY header has no end_header line (file truncated or not a PLY file)");
    }
    std::string_view line = text.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = eol + 1;
    ++line_no;

    if (line_no == 1) {
      if (line != "ply") throw Error(name, "not a PLY file (the first line is not 'ply')");
      continue;
    }
    const auto w = split_words(line);
    if (w.empty()) continue;
    const std::string_view key = w[0];
    if (key == "comment" || key == "obj_info") continue;
    // Names end up in messages and in files we write: plain ASCII only outside comments.
    for (char c : line)
      if ((c < 32 && c != '\t') || c >= 127) throw fail("control or non-ASCII characters in " + shown(line));

    if (key == "end_header") {
      if (w.size() != 1) throw fail("unexpected words after end_header");
      have_end = true;
    } else if (key == "format") {
      if (have_format) throw fail("second format line");
      if (w.size() != 3) throw fail("expected 'format <type> 1.0', got " + shown(line));
      if (w[1] == "binary_big_endian")
        throw Error(name, "binary_big_endian PLY is not supported (convert it to binary_little_endian)");
      if (w[1] == "ascii") h.format = PlyFormat::ascii;
      else if (w[1] == "binary_little_endian") h.format = PlyFormat::binary_little_endian;
      else throw fail("unknown PLY format " + shown(w[1]));
      if (w[2] != "1.0") throw fail("unsupported PLY version " + shown(w[2]) + " (expected 1.0)");
      have_format = true;
    } else if (key == "element") {
      if (w.size() != 3) throw fail("expected 'element <name> <count>', got " + shown(line));
      PlyElement e;
      e.name = std::string(w[1]);
      const auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
        throw fail("element " + shown(w[1]) + " has an invalid count " + shown(w[2]));
      for (const PlyElement& other : h.elements)
        if (other.name == e.name) throw fail("element " + shown(w[1]) + " is declared twice");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) throw fail("property declared before any element");
      PlyElement& e = h.elements.back();
      PlyProperty p;
      if (w.size() >= 2 && w[1] == "list") {
        if (w.size() != 5) throw fail("expected 'property list <count type> <item type> <name>', got " + shown(line));
        p.is_list = true;
        p.name = std::string(w[4]);
        if (!parse_type(w[2], p.count_type))
          throw fail("list property " + shown(w[4]) + " has unknown count type " + shown(w[2]));
        if (!is_integer(p.count_type))
          throw fail("list property " + shown(w[4]) + " has a non-integer count type " + shown(w[2]));
        if (!parse_type(w[3], p.type))
          throw fail("list property " + shown(w[4]) + " has unknown item type " + shown(w[3]));
      } else {
        if (w.size() != 3) throw fail("expected 'property <type> <name>', got " + shown(line));
        p.name = std::string(w[2]);
        if (!parse_type(w[1], p.type))
          throw fail("property " + shown(w[2]) + " of element " + shown(e.name) + " has unknown type " +
                     shown(w[1]));
      }
      for (const PlyProperty& other : e.properties)
        if (other.name == p.name)
          throw fail("property " + shown(p.name) + " of element " + shown(e.name) + " is declared twice");
      e.properties.push_back(std::move(p));
    } else {
      throw fail("unknown header keyword " + shown(key));
    }
  }
  if (!have_format) throw Error(name, "PLY header has no format line");
  h.data_offset = pos;
  return h;
}

}  // namespace goris::ply_detail
