#pragma once
// 3D Gaussian PLY files in the layout every 3DGS viewer reads (docs/design/conventions.md, PLY
// files): one `vertex` element with
//   x y z nx ny nz f_dc_0..2 f_rest_0..M-1 opacity scale_0..2 rot_0..3 [extra float properties...]
// values stored before activation (logit opacity, log scales, unnormalised w,x,y,z quaternions), f_rest
// channel-major per Gaussian: f_rest[c * (K-1) + (k-1)] is coefficient k >= 1 of colour channel c, with
// K = (sh_degree + 1)^2.
//
// Reading accepts binary_little_endian and ascii files written by any software: properties are mapped
// by name in any order, and any integer or floating-point property type is converted to float. Other
// elements (faces...) are skipped. NaN and infinite values are rejected (goris::Error naming the vertex
// and property). Writing always produces binary_little_endian in the standard order and goes through a
// temporary file that is renamed into place. read(write(x)) == x bit for bit, and write(read(f)) == f
// byte for byte for files we wrote.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace goris {

struct GaussianPly {
  size_t count = 0;
  int sh_degree = 0;               // 0..3
  std::vector<float> positions;    // [N][3]
  std::vector<float> normals;      // [N][3]; zeros when the file has none
  std::vector<float> f_dc;         // [N][3]
  std::vector<float> f_rest;       // [N][3 * (K-1)], channel-major per Gaussian, exactly as in the file
  std::vector<float> opacity;      // [N] logit
  std::vector<float> scales;       // [N][3] log
  std::vector<float> rotations;    // [N][4] w, x, y, z
  // Every other vertex property (diffuse_0..2, fresnel_0..2, roughness, region, label...), [N] each,
  // in file order.
  std::vector<std::pair<std::string, std::vector<float>>> extras;

  // The extra property called `name`, or null.
  const std::vector<float>* extra(const std::string& name) const;
  // Number of f_rest values per Gaussian for sh_degree: 0, 9, 24 or 45.
  static size_t rest_per_gaussian(int sh_degree);
  // Throws goris::Error(what, ...) when an array size does not match count / sh_degree, an extra is
  // misnamed (empty, whitespace, a standard property's name) or named twice.
  void check_consistent(const std::string& what) const;
};

// Reads a 3D Gaussian PLY file; every problem throws goris::Error naming the file.
GaussianPly read_ply(const std::filesystem::path& path);
// The same from memory (fuzzing, tests); `name_for_errors` stands for the file in messages.
GaussianPly parse_ply(const uint8_t* data, size_t size, const std::string& name_for_errors);
// Writes binary_little_endian in the standard layout via a temporary file in the same folder.
void write_ply(const std::filesystem::path& path, const GaussianPly& ply);

// Human-readable summary for `goris info`: format, count, SH degree, extra properties, position
// bounds, opacity range after sigmoid.
std::string ply_summary(const std::filesystem::path& path);
// The summary's last lines, for a model of any file format: position bounds and opacity range (nothing
// for an empty model).
std::string gaussian_stats(const GaussianPly& g);

}  // namespace goris
