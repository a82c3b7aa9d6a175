#pragma once
// The data section of a PLY file (internal to core/io/ply_*.cpp): walking over elements that come before
// the vertex element, and converting the vertex element's properties to float arrays.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/ply_header.h"

namespace goris::ply_detail {

// Where one vertex property's values go: dst[i * stride + offset] for vertex i.
struct Column {
  const PlyProperty* prop = nullptr;
  float* dst = nullptr;
  size_t stride = 1, offset = 0;
  size_t byte_offset = 0;  // within a binary row
  // > 0: an infinite value is read as +-saturate (a logit of alpha 0 or 1, e.g. opacity); NaN is still an error.
  float saturate = 0.0f;
};

// Whitespace-separated words of an ASCII PLY body.
struct AsciiTokens {
  const char* p;
  const char* end;
  // The next word, or an empty view at the end of the data.
  std::string_view next();
};

// Byte offset just past binary element `e`, which starts at `pos`.
size_t skip_binary_element(const PlyElement& e, const uint8_t* data, size_t size, size_t pos,
                           const std::string& name);
void skip_ascii_element(const PlyElement& e, AsciiTokens& tok, const std::string& name);

// Fills every column for `count` vertices; non-finite values and malformed or missing data throw
// goris::Error(name, ...) naming the vertex and the property.
void read_binary_vertices(const uint8_t* rows, size_t count, size_t row_bytes, const std::vector<Column>& cols,
                          const std::string& name);
void read_ascii_vertices(AsciiTokens& tok, size_t count, const std::vector<Column>& cols, const std::string& name,
                         size_t data_bytes);

}  // namespace goris::ply_detail
