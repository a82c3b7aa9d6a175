#pragma once
// Helpers shared by the camera / image / data set tests: writing small files and checking error messages.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include "core/io/image.h"
#include "core/util/error.h"

namespace goris::test {

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

inline void write_bytes(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A w x h PNG whose every pixel is `value` in each of `channels` channels.
inline void write_png(const std::filesystem::path& p, int w, int h, int channels = 3, float value = 0.5f) {
  std::filesystem::create_directories(p.parent_path());
  Image im(w, h, channels);
  for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = value;
  save_png(p, im);
}

// Preamble (version 1.0) + `header` + raw f8 `values`.
inline std::vector<uint8_t> npy_from_header(const std::string& header, const std::vector<double>& values) {
  const uint8_t preamble[10] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, uint8_t(header.size() & 0xff), uint8_t(header.size() >> 8)};
  std::vector<uint8_t> b(10 + header.size());
  std::memcpy(b.data(), preamble, 10);
  std::memcpy(b.data() + 10, header.data(), header.size());
  const size_t at = b.size();
  b.resize(at + values.size() * 8);
  if (!values.empty()) std::memcpy(b.data() + at, values.data(), values.size() * 8);
  return b;
}

// A .npy file (version 1.0) holding `values` as little-endian f8 with the given shape.
inline std::vector<uint8_t> npy_bytes(const std::vector<size_t>& shape, const std::vector<double>& values,
                                      const std::string& descr = "<f8", bool fortran = false) {
  std::string shp = "(";
  for (size_t s : shape) shp += std::to_string(s) + ", ";
  shp += ")";
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
                       ", 'shape': " + shp + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  return npy_from_header(header, values);
}


// Runs f, expects a goris::Error whose message contains every one of `parts`, and returns the message.
template <class F>
std::string expect_error(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
  } catch (const goris::Error& e) {
    const std::string msg = e.what();
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
    return msg;
  }
  ADD_FAILURE() << "expected a goris::Error";
  return "";
}

}  // namespace goris::test

namespace goris::test {
inline std::string read_text_file_for_test(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace goris::test
