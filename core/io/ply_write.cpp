// Writing 3D Gaussian PLY files: binary little endian, standard 3DGS property order, extras last.
// The file is assembled in row chunks and written to a temporary file beside the target, which is
// renamed into place only once everything is written (core/io/file_bytes.h), so a failed write never
// damages an existing file.
#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/io/file_bytes.h"
#include "core/io/ply.h"
#include "core/util/error.h"

static_assert(std::endian::native == std::endian::little, "the PLY writer assumes a little-endian host");

namespace goris {
namespace {

std::string header_text(const GaussianPly& g) {
  std::string h = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(g.count) + "\n";
  auto prop = [&](const std::string& n) { h.append("property float ").append(n).append("\n"); };
  for (const char* n : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"}) prop(n);
  const size_t rest = GaussianPly::rest_per_gaussian(g.sh_degree);
  for (size_t k = 0; k < rest; ++k) prop("f_rest_" + std::to_string(k));
  for (const char* n : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) prop(n);
  for (const auto& e : g.extras) prop(e.first);
  return h + "end_header\n";
}

// Closes the file on every path out of the writer.
struct FileCloser {
  FILE* f = nullptr;
  ~FileCloser() {
    if (f) std::fclose(f);
  }
};

}  // namespace

void write_ply(const std::filesystem::path& path, const GaussianPly& g) {
  const std::string where = path.string();
  g.check_consistent(where);
  write_via_temp_file(path, [&](const std::filesystem::path& tmp) {
    FileCloser file{std::fopen(tmp.c_str(), "wb")};
    if (!file.f) throw Error(where, "cannot create temporary file " + tmp.string() + ": " + std::strerror(errno));
    auto failed = [&]() {
      return Error(where, "write failed (" + std::string(std::strerror(errno)) + "); the file was left unchanged");
    };
    auto put = [&](const void* p, size_t bytes) {
      if (bytes && std::fwrite(p, 1, bytes, file.f) != bytes) throw failed();
    };
    const std::string header = header_text(g);
    put(header.data(), header.size());

    const size_t rest = GaussianPly::rest_per_gaussian(g.sh_degree);
    const size_t row = 9 + rest + 8 + g.extras.size();
    constexpr size_t kChunk = 16384;
    std::vector<float> buf(std::min(g.count, kChunk) * row);
    for (size_t r0 = 0; r0 < g.count; r0 += kChunk) {
      const size_t r1 = std::min(g.count, r0 + kChunk);
      float* out = buf.data();
      for (size_t i = r0; i < r1; ++i) {
        auto copy = [&](const std::vector<float>& v, size_t per) {
          std::memcpy(out, v.data() + i * per, per * sizeof(float));
          out += per;
        };
        copy(g.positions, 3);
        if (g.normals.empty()) {
          std::fill(out, out + 3, 0.0f);
          out += 3;
        } else {
          copy(g.normals, 3);
        }
        copy(g.f_dc, 3);
        copy(g.f_rest, rest);
        copy(g.opacity, 1);
        copy(g.scales, 3);
        copy(g.rotations, 4);
        for (const auto& e : g.extras) *out++ = e.second[i];
      }
      put(buf.data(), (r1 - r0) * row * sizeof(float));
    }
    const int closed = std::fclose(file.f);
    file.f = nullptr;
    if (closed != 0) throw failed();
  });
}

}  // namespace goris
