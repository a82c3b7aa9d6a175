// Reading 3D Gaussian PLY files: the header (ply_header.cpp) says where every vertex property lives; each
// property gets a destination (array, stride, offset) by name, checks that every required one is there,
// then hands the data to ply_vertex_data.cpp.
#include <algorithm>
#include <bit>
#include <charconv>
#include <string_view>

#include "core/io/ply.h"
#include "core/io/ply_header.h"
#include "core/io/ply_vertex_data.h"
#include "core/io/splat_codec.h"
#include "core/util/error.h"

static_assert(std::endian::native == std::endian::little, "the PLY reader assumes a little-endian host");

namespace goris::ply_detail {
namespace {

// Standard names that are not extras: what array they fill and where.
enum class Slot { position, normal, dc, rest, opacity, scale, rotation, extra };
struct Target {
  Slot slot = Slot::extra;
  size_t index = 0;
};

// "f_rest_<n>" with n written the canonical way (no sign, no leading zeros); false for anything else.
bool rest_index(std::string_view name, size_t& index) {
  constexpr std::string_view prefix = "f_rest_";
  if (name.substr(0, prefix.size()) != prefix) return false;
  const std::string_view digits = name.substr(prefix.size());
  if (digits.empty() || digits.size() > 6 || (digits.size() > 1 && digits[0] == '0')) return false;
  for (char c : digits)
    if (c < '0' || c > '9') return false;
  std::from_chars(digits.data(), digits.data() + digits.size(), index);
  return true;
}

Target classify(std::string_view n) {
  static const struct {
    const char* name;
    Slot slot;
    size_t index;
  } fixed[] = {{"x", Slot::position, 0},   {"y", Slot::position, 1},   {"z", Slot::position, 2},
               {"nx", Slot::normal, 0},    {"ny", Slot::normal, 1},    {"nz", Slot::normal, 2},
               {"f_dc_0", Slot::dc, 0},    {"f_dc_1", Slot::dc, 1},    {"f_dc_2", Slot::dc, 2},
               {"opacity", Slot::opacity, 0},
               {"scale_0", Slot::scale, 0}, {"scale_1", Slot::scale, 1}, {"scale_2", Slot::scale, 2},
               {"rot_0", Slot::rotation, 0}, {"rot_1", Slot::rotation, 1}, {"rot_2", Slot::rotation, 2},
               {"rot_3", Slot::rotation, 3}};
  for (const auto& f : fixed)
    if (n == f.name) return {f.slot, f.index};
  size_t k = 0;
  if (rest_index(n, k)) return {Slot::rest, k};
  return {};
}

}  // namespace

bool is_standard_name(std::string_view name) { return classify(name).slot != Slot::extra; }

GaussianPly parse_gaussians(const uint8_t* data, size_t size, const std::string& name, PlyHeader& header) {
  header = parse_header(data, size, name);
  const bool ascii = header.format == PlyFormat::ascii;

  size_t vi = header.elements.size();
  for (size_t i = 0; i < header.elements.size(); ++i)
    if (header.elements[i].name == "vertex") vi = i;
  if (vi == header.elements.size()) throw Error(name, "PLY file has no 'vertex' element");
  const PlyElement& ve = header.elements[vi];
  for (const PlyProperty& p : ve.properties)
    if (p.is_list)
      throw Error(name, "vertex property '" + p.name + "' is a list; 3D Gaussian PLY vertices hold scalars only");

  // Elements before the vertex element are walked over; those after it are never read.
  size_t pos = header.data_offset;
  AsciiTokens tok{reinterpret_cast<const char*>(data) + pos, reinterpret_cast<const char*>(data) + size};
  for (size_t i = 0; i < vi; ++i) {
    if (ascii) skip_ascii_element(header.elements[i], tok, name);
    else pos = skip_binary_element(header.elements[i], data, size, pos, name);
  }

  // Map properties to slots by name.
  std::vector<Target> targets;
  bool seen[int(Slot::extra)][4] = {};
  size_t n_rest = 0, max_rest = 0;
  for (const PlyProperty& p : ve.properties) {
    const Target t = classify(p.name);
    targets.push_back(t);
    if (t.slot == Slot::rest) ++n_rest, max_rest = std::max(max_rest, t.index + 1);
    else if (t.slot != Slot::extra) seen[int(t.slot)][t.index] = true;
  }
  static const char* required[][4] = {{"x", "y", "z", nullptr}, {"nx", "ny", "nz", nullptr},
                                      {"f_dc_0", "f_dc_1", "f_dc_2", nullptr}, {nullptr},
                                      {"opacity", nullptr}, {"scale_0", "scale_1", "scale_2", nullptr},
                                      {"rot_0", "rot_1", "rot_2", "rot_3"}};
  std::string missing;
  int n_missing = 0;
  for (int s = 0; s < int(Slot::extra); ++s)
    for (int k = 0; k < 4 && required[s][k]; ++k)
      if (!seen[s][k] && Slot(s) != Slot::normal)
        missing += (n_missing++ ? ", '" : "'") + std::string(required[s][k]) + "'";
  if (n_missing)
    throw Error(name, std::string("missing required vertex ") + (n_missing > 1 ? "properties " : "property ") +
                          missing);
  const bool has_normals = seen[int(Slot::normal)][0] || seen[int(Slot::normal)][1] || seen[int(Slot::normal)][2];
  for (int k = 0; k < 3; ++k)
    if (has_normals && !seen[int(Slot::normal)][k])
      throw Error(name, "incomplete normals: missing vertex property '" +
                            std::string(required[int(Slot::normal)][k]) + "'");
  int degree = -1;
  for (int d = 0; d <= 3; ++d)
    if (n_rest == GaussianPly::rest_per_gaussian(d)) degree = d;
  if (degree < 0)
    throw Error(name, "has " + std::to_string(n_rest) +
                          " f_rest properties; expected 0, 9, 24 or 45 (SH degree 0, 1, 2 or 3)");
  if (max_rest > n_rest)
    throw Error(name, "f_rest properties are not numbered 0.." + std::to_string(n_rest - 1) + " (found 'f_rest_" +
                          std::to_string(max_rest - 1) + "')");

  // Check the data is there before allocating anything the size of the declared count.
  const size_t n = size_t(ve.count);
  const size_t row_bytes = ve.binary_stride();
  if (ascii) {
    const size_t left = size_t(tok.end - tok.p);
    if (ve.count > left / ve.properties.size())
      throw Error(name, "truncated: the header declares " + std::to_string(ve.count) + " vertices of " +
                            std::to_string(ve.properties.size()) + " values but only " + std::to_string(left) +
                            " bytes of data follow");
  } else if (ve.count > (size - pos) / row_bytes) {
    throw Error(name, "truncated: the header declares " + std::to_string(ve.count) + " vertices of " +
                          std::to_string(row_bytes) + " bytes but only " + std::to_string(size - pos) +
                          " bytes of vertex data follow");
  }

  GaussianPly g;
  g.count = n;
  g.sh_degree = degree;
  g.positions.resize(n * 3);
  g.normals.assign(n * 3, 0.0f);
  g.f_dc.resize(n * 3);
  g.f_rest.resize(n * n_rest);
  g.opacity.resize(n);
  g.scales.resize(n * 3);
  g.rotations.resize(n * 4);
  for (size_t j = 0; j < ve.properties.size(); ++j)
    if (targets[j].slot == Slot::extra) g.extras.emplace_back(ve.properties[j].name, std::vector<float>(n));

  std::vector<Column> cols;
  size_t byte_offset = 0, extra_i = 0;
  for (size_t j = 0; j < ve.properties.size(); ++j) {
    Column c;
    c.prop = &ve.properties[j];
    c.byte_offset = byte_offset;
    byte_offset += type_size(c.prop->type);
    c.offset = targets[j].index;
    switch (targets[j].slot) {
      case Slot::position: c.dst = g.positions.data(), c.stride = 3; break;
      case Slot::normal: c.dst = g.normals.data(), c.stride = 3; break;
      case Slot::dc: c.dst = g.f_dc.data(), c.stride = 3; break;
      case Slot::rest: c.dst = g.f_rest.data(), c.stride = n_rest; break;
      case Slot::opacity:
        // Other tools write alpha 1 or 0 as an infinite logit (an SPZ opacity byte of 255, decoded by
        // splat-transform): read as the finite logit our own 8-bit decoders give those alphas.
        c.dst = g.opacity.data(), c.stride = 1, c.saturate = splat_detail::logit_of_alpha(1.0f);
        break;
      case Slot::scale: c.dst = g.scales.data(), c.stride = 3; break;
      case Slot::rotation: c.dst = g.rotations.data(), c.stride = 4; break;
      case Slot::extra: c.dst = g.extras[extra_i++].second.data(), c.stride = 1; break;
    }
    cols.push_back(c);
  }
  if (n == 0) return g;
  if (ascii) read_ascii_vertices(tok, n, cols, name, size - header.data_offset);
  else read_binary_vertices(data + pos, n, row_bytes, cols, name);
  return g;
}

}  // namespace goris::ply_detail

namespace goris {

GaussianPly parse_ply(const uint8_t* data, size_t size, const std::string& name_for_errors) {
  ply_detail::PlyHeader header;
  return ply_detail::parse_gaussians(data, size, name_for_errors, header);
}

GaussianPly read_ply(const std::filesystem::path& path) {
  ply_detail::FileView file(path);
  return parse_ply(file.data(), file.size(), path.string());
}

}  // namespace goris
