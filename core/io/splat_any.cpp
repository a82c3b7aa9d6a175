// Model files of any supported format (core/io/splat_formats.h): reading by content, writing by name.
#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/io/file_bytes.h"
#include "core/io/ply_header.h"
#include "core/io/splat_codec.h"
#include "core/io/splat_formats.h"

namespace goris {
namespace fs = std::filesystem;

namespace {
std::string lower_name(const fs::path& path) {
  std::string n = path.filename().string();
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return n;
}
bool ends_with(const std::string& s, const char* tail) {
  const size_t k = std::strlen(tail);
  return s.size() >= k && s.compare(s.size() - k, k, tail) == 0;
}
}  // namespace

const char* splat_format_name(SplatFormat f) {
  switch (f) {
    case SplatFormat::Ply: return "3D Gaussian PLY";
    case SplatFormat::CompressedPly: return "PlayCanvas compressed PLY";
    case SplatFormat::Spz: return "Niantic SPZ";
    case SplatFormat::Antimatter: return "antimatter15 .splat";
    case SplatFormat::Glb: return "glTF GLB (KHR_gaussian_splatting)";
  }
  return "?";
}

bool is_splat_file_name(const fs::path& path) {
  const std::string n = lower_name(path);
  return ends_with(n, ".ply") || ends_with(n, ".spz") || ends_with(n, ".splat") || ends_with(n, ".glb");
}

SplatFormat splat_format_from_name(const fs::path& path) {
  const std::string n = lower_name(path);
  if (ends_with(n, ".compressed.ply")) return SplatFormat::CompressedPly;
  if (ends_with(n, ".ply")) return SplatFormat::Ply;
  if (ends_with(n, ".spz")) return SplatFormat::Spz;
  if (ends_with(n, ".splat")) return SplatFormat::Antimatter;
  if (ends_with(n, ".glb")) return SplatFormat::Glb;
  throw Error(path.string(), "unknown model file type: expected .ply, .compressed.ply, .spz, .splat or .glb");
}

SplatFormat detect_splat_format(const uint8_t* data, size_t size, const fs::path& path) {
  if (size >= 2 && data[0] == 0x1f && data[1] == 0x8b) return SplatFormat::Spz;
  if (size >= 4 && splat_detail::get_u32(data) == 0x5053474e) return SplatFormat::Spz;  // SPZ 4: refused by the decoder
  if (size >= 4 && std::memcmp(data, "glTF", 4) == 0) return SplatFormat::Glb;
  if (size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r')) {
    // A header with a `chunk` element is PlayCanvas' compressed layout; anything else is read as 3DGS.
    const ply_detail::PlyHeader h = ply_detail::parse_header(data, size, path.string());
    for (const auto& e : h.elements)
      if (e.name == "chunk") return SplatFormat::CompressedPly;
    return SplatFormat::Ply;
  }
  const std::string n = lower_name(path);
  if (ends_with(n, ".splat")) return SplatFormat::Antimatter;
  if (ends_with(n, ".spz")) return SplatFormat::Spz;  // the decoder says what is wrong with it
  if (ends_with(n, ".ply")) return SplatFormat::Ply;
  if (ends_with(n, ".glb")) return SplatFormat::Glb;
  throw Error(path.string(), "not a model file: neither PLY, SPZ, GLB nor (by its name) .splat");
}

GaussianPly parse_gaussians_any(const uint8_t* data, size_t size, const fs::path& path) {
  const std::string name = path.string();
  switch (detect_splat_format(data, size, path)) {
    case SplatFormat::Ply: return parse_ply(data, size, name);
    case SplatFormat::CompressedPly: return decode_compressed_ply(data, size, name);
    case SplatFormat::Spz: return decode_spz(data, size, name);
    case SplatFormat::Antimatter: return decode_antimatter_splat(data, size, name);
    case SplatFormat::Glb: return decode_glb(data, size, name);
  }
  throw Error(name, "unknown model format");
}

GaussianPly read_gaussians(const fs::path& path) {
  const ply_detail::FileView file(path);  // memory-mapped where possible
  return parse_gaussians_any(file.data(), file.size(), path);
}

void write_gaussians(const fs::path& path, const GaussianPly& g) {
  const std::string name = path.string();
  std::vector<uint8_t> bytes;
  switch (splat_format_from_name(path)) {
    case SplatFormat::Ply: write_ply(path, g); return;
    case SplatFormat::CompressedPly: bytes = encode_compressed_ply(g, name); break;
    case SplatFormat::Spz: bytes = encode_spz(g, name); break;
    case SplatFormat::Antimatter: bytes = encode_antimatter_splat(g, name); break;
    case SplatFormat::Glb: bytes = encode_glb(g, name); break;
  }
  write_file_bytes(path, bytes.data(), bytes.size());
}

std::string gaussians_summary(const fs::path& path) {
  const ply_detail::FileView bytes(path);
  const SplatFormat f = detect_splat_format(bytes.data(), bytes.size(), path);
  if (f == SplatFormat::Ply) return ply_summary(path);
  const GaussianPly g = parse_gaussians_any(bytes.data(), bytes.size(), path);
  std::string s = path.string() + ": " + splat_format_name(f);
  if (f == SplatFormat::Spz) {
    const auto raw = splat_detail::gzip_decompress(bytes.data(), bytes.size(), 16, path.string(), /*prefix_only=*/true);
    s += " version " + std::to_string(splat_detail::get_u32(raw.data() + 4));
  }
  s += " (" + std::to_string(bytes.size()) + " bytes)\n";
  s += "  " + std::to_string(g.count) + " Gaussians, SH degree " + std::to_string(g.sh_degree) + " (" +
       std::to_string(GaussianPly::rest_per_gaussian(g.sh_degree)) + " f_rest values each)\n";
  return s + gaussian_stats(g);
}

}  // namespace goris
