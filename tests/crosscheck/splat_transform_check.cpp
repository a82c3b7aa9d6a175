// Cross-check of our splat formats with other software: PlayCanvas' splat-transform (npm, installed by
// ./dev setup into tools/node_modules). Both directions, on a random model of SH degree 3:
//   - each of our exports (SPZ, compressed PLY, .splat; it reads no GLB) converted back to PLY by splat-transform must agree
//     with the source within the format's quantization, and with what our own reader makes of the file;
//   - splat-transform's SPZ (version 3), compressed PLY and GLB written from our PLY must open in our readers
//     and agree with the source within the quantization; its default SPZ (version 4, zstd) must be refused
//     with a message saying so.
// Exits 77 (ctest: skipped) with GORIS_TEST_SKIPPED and the reason when node or splat-transform is absent;
// 1 when a check fails.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/io/splat_compare.h"
#include "core/io/splat_formats.h"
#include "tests/support/splat_test_model.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

int failures = 0;

void expect_le(const char* what, const std::string& where, double value, double bound) {
  if (value <= bound) return;
  std::printf("FAILED: %s: %s = %.6g, bound %.6g\n", where.c_str(), what, value, bound);
  ++failures;
}

// Quantization bounds (tests/unit/test_splat_formats.cpp explains each) and slack for a decoder that rounds
// differently from ours.
struct Bounds {
  double position, scale, rotation, opacity, f_dc, f_rest;
};
constexpr Bounds kSpz{std::sqrt(3.0) * 0.5 / 4096 + 1e-6, 0.5 / 16 + 1e-5, 0.25, 0.5 / 255 + 1e-5, 0.5 / (0.15 * 255) + 1e-5,
                      8.5 / 128 + 1e-5};
constexpr Bounds kCompressedPly{std::sqrt(3.0) * 0.5 * 10.0 / 1023 + 1e-5, 0.5 * 11.0 / 1023 + 1e-5, 0.25, 0.5 / 255 + 1e-5,
                                0.5 * 4.0 / 255 + 1e-4, 1.0 / 32 + 1e-5};
// .splat rotations: antimatter15's viewer decodes a byte v as (v - 128) / 128, as we do; splat-transform as
// v / 127.5 - 1, which turns a rotation by up to about a degree more.
constexpr Bounds kSplat{1e-6, 1e-5, 2.0, 0.5 / 255 + 1e-5, 0.5 / 255 / splat_detail::kShC0 + 1e-5, INFINITY};
constexpr Bounds kSameSplatFile{1e-6, 1e-5, 1.2, 1e-4, 1e-4, INFINITY};
// GLB: float32 throughout.
constexpr Bounds kGlb{1e-5, 1e-5, 0.05, 1e-5, 1e-5, 1e-5};
// Two decoders of the same file: float rounding only (the rotation angle of nearly equal unit quaternions
// is ill-conditioned in float, hence its larger bound).
constexpr Bounds kSameFile{1e-5, 1e-4, 0.05, 1e-4, 1e-4, 1e-4};

void check(const std::string& where, const GaussianPly& ref, const GaussianPly& got, const Bounds& b, bool rest) {
  if (ref.count != got.count) {
    std::printf("FAILED: %s: %zu Gaussians, expected %zu\n", where.c_str(), got.count, ref.count);
    ++failures;
    return;
  }
  const ModelDiff d = compare_models(ref, got, match_by_position(ref, got));
  std::printf("%s:\n%s", where.c_str(), d.table().c_str());
  expect_le("position", where, d.position.max, b.position);
  expect_le("scale", where, d.scale.max, b.scale);
  expect_le("rotation", where, d.rotation.max, b.rotation);
  expect_le("opacity", where, d.opacity.max, b.opacity);
  expect_le("f_dc", where, d.f_dc.max, b.f_dc);
  if (rest) {
    expect_le("f_rest", where, d.f_rest.max, b.f_rest);
    if (got.sh_degree != ref.sh_degree) {
      std::printf("FAILED: %s: SH degree %d, expected %d\n", where.c_str(), got.sh_degree, ref.sh_degree);
      ++failures;
    }
  }
}

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

bool run(const std::string& cmd, const fs::path& log) {
  const std::string full = cmd + " >" + quoted(log) + " 2>&1";
  const int rc = std::system(full.c_str());
  if (rc != 0) {
    std::printf("FAILED: %s exited with %d; its output is in %s\n", cmd.c_str(), rc, log.string().c_str());
    ++failures;
  }
  return rc == 0;
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path source_root = GORIS_SOURCE_DIR;
  const fs::path tool = std::getenv("GORIS_SPLAT_TRANSFORM") ? fs::path(std::getenv("GORIS_SPLAT_TRANSFORM"))
                                                             : source_root / "tools/node_modules/.bin/splat-transform";
  if (std::system("command -v node >/dev/null 2>&1") != 0) {
    std::printf("GORIS_TEST_SKIPPED: node is not installed (the cross-check runs PlayCanvas' splat-transform)\n");
    return 77;
  }
  if (!fs::exists(tool)) {
    std::printf("GORIS_TEST_SKIPPED: %s is absent (./dev setup installs it with npm)\n", tool.string().c_str());
    return 77;
  }
  const fs::path dir = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path() / "goris_splat_transform_check";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string st = "node " + quoted(tool) + " -q -w ";

  GaussianPly source = test::random_splat_model(2000, 3, 42);
  for (float& v : source.f_dc) v *= 0.85f;  // colours inside 0..1, which .splat's bytes hold
  const fs::path source_ply = dir / "source.ply";
  write_gaussians(source_ply, source);
  GaussianPly plain = source;  // what the formats can hold: the standard attributes
  plain.normals.clear();
  plain.extras.clear();

  // Ours -> splat-transform -> PLY.
  struct Ours {
    const char* file;
    Bounds bounds, same_file;
    bool rest;
  };
  for (const Ours& o : {Ours{"ours.spz", kSpz, kSameFile, true}, Ours{"ours.compressed.ply", kCompressedPly, kSameFile, true},
                        Ours{"ours.splat", kSplat, kSameSplatFile, false}}) {
    const fs::path file = dir / o.file, back = dir / (std::string(o.file) + ".back.ply");
    write_gaussians(file, plain);
    if (!run(st + quoted(file) + " " + quoted(back), dir / (std::string(o.file) + ".log"))) continue;
    const GaussianPly theirs = read_gaussians(back), ours = read_gaussians(file);
    check(std::string(o.file) + " read by splat-transform vs the source", plain, theirs, o.bounds, o.rest);
    check(std::string(o.file) + " read by splat-transform vs read by us", ours, theirs, o.same_file, o.rest);
  }

  // Our PLY -> splat-transform -> SPZ 3 / compressed PLY -> our readers.
  struct Theirs {
    const char* file;
    const char* options;
    Bounds bounds;
  };
  for (const Theirs& t : {Theirs{"theirs.spz", "--spz-version 3 ", kSpz}, Theirs{"theirs.compressed.ply", "", kCompressedPly},
                          Theirs{"theirs.glb", "", kGlb}}) {
    const fs::path file = dir / t.file;
    if (!run("node " + quoted(tool) + " -q -w " + t.options + quoted(source_ply) + " " + quoted(file),
             dir / (std::string(t.file) + ".log")))
      continue;
    try {
      check(std::string(t.file) + " (splat-transform) read by us vs the source", plain, read_gaussians(file), t.bounds, true);
    } catch (const Error& e) {
      std::printf("FAILED: %s\n", e.what());
      ++failures;
    }
  }
  // Their default SPZ is version 4 (zstd), which we do not read: the error must say so.
  const fs::path v4 = dir / "theirs_v4.spz";
  if (run(st + quoted(source_ply) + " " + quoted(v4), dir / "theirs_v4.log")) {
    try {
      read_gaussians(v4);
      std::printf("FAILED: an SPZ version 4 file was read without an error\n");
      ++failures;
    } catch (const Error& e) {
      const std::string m = e.what();
      if (m.find(v4.string()) == std::string::npos || m.find("version 4") == std::string::npos) {
        std::printf("FAILED: the SPZ version 4 error does not name the file and the version: %s\n", m.c_str());
        ++failures;
      } else {
        std::printf("theirs_v4.spz: refused as expected: %s\n", m.c_str());
      }
    }
  }
  std::printf("%s (%d failures); files in %s\n", failures ? "FAILED" : "passed", failures, dir.string().c_str());
  return failures ? 1 : 0;
}
