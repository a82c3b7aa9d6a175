#pragma once
// The header of a PLY file (internal to core/io/ply_*.cpp): format, elements and their properties.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/ply.h"

namespace goris::ply_detail {

enum class PlyFormat { ascii, binary_little_endian };

enum class PlyType : uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;  // item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::u8;  // lists only
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  bool has_list() const;
  // Bytes of one item in a binary file; only meaningful without list properties.
  size_t binary_stride() const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::binary_little_endian;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // first byte after the end_header line
};

size_t type_size(PlyType t);
const char* type_name(PlyType t);

// Parses everything up to and including `end_header`; throws goris::Error(name, ...) for anything that
// is not a well-formed little-endian or ascii PLY header.
PlyHeader parse_header(const uint8_t* data, size_t size, const std::string& name);

// parse_ply that also hands back the header (ply_summary reports the format and other elements).
GaussianPly parse_gaussians(const uint8_t* data, size_t size, const std::string& name, PlyHeader& header);

// True for the names that read_ply maps to a standard array (x, nx, f_dc_0, f_rest_<n>, opacity, ...).
bool is_standard_name(std::string_view name);

// A whole file's bytes, memory-mapped when possible; throws goris::Error naming the file when it is
// missing, a folder or unreadable.
class FileView {
 public:
  explicit FileView(const std::filesystem::path& path);
  ~FileView();
  FileView(const FileView&) = delete;
  FileView& operator=(const FileView&) = delete;
  const uint8_t* data() const { return map_ ? static_cast<const uint8_t*>(map_) : copy_.data(); }
  size_t size() const { return map_ ? size_ : copy_.size(); }

 private:
  void* map_ = nullptr;
  size_t size_ = 0;
  std::vector<uint8_t> copy_;
};

}  // namespace goris::ply_detail
