#pragma once
// Writing NumPy .npy files (format 1.0, little-endian, C order) - the counterpart of npy.h's reader, for
// intermediate arrays a person may want to open in Python (stage-2 maps, selections).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace goris {

// The bytes of a .npy file: `descr` is the NumPy dtype string ("<f4", "|u1", ...), `data` holds
// product(shape) elements of that type.
std::vector<std::uint8_t> npy_bytes(const std::string& descr, const std::vector<std::size_t>& shape, const void* data,
                                    std::size_t data_bytes);

// float32 / uint8 arrays written through a temporary file renamed into place.
void save_npy(const std::filesystem::path& path, const std::vector<float>& data, const std::vector<std::size_t>& shape);
void save_npy(const std::filesystem::path& path, const std::vector<std::uint8_t>& data,
              const std::vector<std::size_t>& shape);

}  // namespace goris
