#pragma once
// A small reader for NumPy .npy files (format versions 1-3): little-endian f4, f8, i1, i2, i4, i8, u1,
// u2, u4, u8 and b1 in C order, converted to double. Fortran order, big-endian data, other dtypes,
// truncated files and malformed headers are rejected with a goris::Error naming the file.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace goris {

struct NpyArray {
  std::vector<size_t> shape;  // empty for a 0-d (scalar) array
  std::vector<double> data;   // row-major (C order), product(shape) values

  // Element (i, j) of a 2-d array.
  double at(size_t i, size_t j) const { return data[i * shape[1] + j]; }
};

NpyArray load_npy(const std::filesystem::path& path);
// The same from memory; `name_for_errors` stands for the file in messages.
NpyArray parse_npy(const uint8_t* bytes, size_t n, const std::string& name_for_errors);

}  // namespace goris
