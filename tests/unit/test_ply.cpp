// 3D Gaussian PLY reading and writing (core/io/ply.h): bit-exact round trips, the standard header layout,
// files written by other software (ASCII, other types, other orders, other elements), every kind of bad
// input, and the external garden fixture.
#include <gtest/gtest.h>

#include <bit>
#include <iterator>
#include <cmath>
#include <cstring>
#include <charconv>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>

#include "core/io/npy.h"
#include "core/io/ply.h"
#include "core/scene/sh_layout.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

namespace fs = std::filesystem;
using test::scratch_dir;

// --- helpers -----------------------------------------------------------------------------------------

// Any float that is not NaN or infinite, plus the awkward ones (denormals, -0, extremes) at fixed places.
float random_float(std::mt19937& rng) {
  for (;;) {
    const float f = std::bit_cast<float>(uint32_t(rng()));
    if (std::isfinite(f)) return f;
  }
}

GaussianPly random_ply(size_t n, int degree, bool with_extras, uint32_t seed) {
  std::mt19937 rng(seed);
  GaussianPly g;
  g.count = n;
  g.sh_degree = degree;
  auto fill = [&](std::vector<float>& v, size_t per) {
    v.resize(n * per);
    for (float& f : v) f = random_float(rng);
  };
  fill(g.positions, 3);
  fill(g.normals, 3);
  fill(g.f_dc, 3);
  fill(g.f_rest, GaussianPly::rest_per_gaussian(degree));
  fill(g.opacity, 1);
  fill(g.scales, 3);
  fill(g.rotations, 4);
  if (with_extras)
    for (const char* name : {"diffuse_0", "diffuse_1", "diffuse_2", "fresnel_0", "fresnel_1", "fresnel_2",
                             "roughness", "region", "label"})
      fill(g.extras.emplace_back(name, std::vector<float>()).second, 1);
  const float specials[] = {-0.0f, 0.0f, std::numeric_limits<float>::denorm_min(),
                            -std::numeric_limits<float>::denorm_min(), 1.17e-39f, -3.3e-42f,
                            std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
                            std::numeric_limits<float>::min()};
  for (size_t i = 0; i < std::size(specials) && i < n; ++i) {
    g.positions[i * 3 + 1] = specials[i];
    g.opacity[i] = specials[i];
    g.f_dc[i * 3] = specials[i];
    if (!g.f_rest.empty()) g.f_rest[i * GaussianPly::rest_per_gaussian(degree)] = specials[i];
    if (with_extras) g.extras.back().second[i] = specials[i];
  }
  return g;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

void expect_identical(const GaussianPly& a, const GaussianPly& b) {
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.sh_degree, b.sh_degree);
  EXPECT_TRUE(same_bits(a.positions, b.positions));
  EXPECT_TRUE(same_bits(a.normals, b.normals));
  EXPECT_TRUE(same_bits(a.f_dc, b.f_dc));
  EXPECT_TRUE(same_bits(a.f_rest, b.f_rest));
  EXPECT_TRUE(same_bits(a.opacity, b.opacity));
  EXPECT_TRUE(same_bits(a.scales, b.scales));
  EXPECT_TRUE(same_bits(a.rotations, b.rotations));
  ASSERT_EQ(a.extras.size(), b.extras.size());
  for (size_t i = 0; i < a.extras.size(); ++i) {
    EXPECT_EQ(a.extras[i].first, b.extras[i].first);
    EXPECT_TRUE(same_bits(a.extras[i].second, b.extras[i].second)) << a.extras[i].first;
  }
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

template <typename T>
void append(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

// The standard 3DGS vertex property names for an SH degree, in the order every viewer expects.
std::vector<std::string> standard_names(int degree) {
  std::vector<std::string> n = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (size_t k = 0; k < GaussianPly::rest_per_gaussian(degree); ++k) n.push_back("f_rest_" + std::to_string(k));
  for (const char* s : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) n.push_back(s);
  return n;
}

// A header with one all-float vertex element holding `names`.
std::string float_header(const std::string& format, size_t count, const std::vector<std::string>& names) {
  std::string h = "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(count) + "\n";
  for (const auto& n : names) h += "property float " + n + "\n";
  return h + "end_header\n";
}

// The goris::Error message of f(); fails the test when f throws nothing or something else.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected goris::Error, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected goris::Error, nothing was thrown";
  return "";
}

void expect_mentions(const std::string& msg, std::initializer_list<std::string> parts) {
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

// Writes `bytes` to a file and checks that reading it fails with a message naming the file and `parts`.
void expect_read_error(const fs::path& dir, const std::string& file, const std::string& bytes,
                       std::initializer_list<std::string> parts) {
  const fs::path p = dir / file;
  write_bytes(p, bytes);
  SCOPED_TRACE(file);
  const std::string msg = error_of([&] { read_ply(p); });
  expect_mentions(msg, {p.string()});
  expect_mentions(msg, parts);
}

// --- round trip and layout --------------------------------------------------------------------------

TEST(Ply, RoundTripIsBitExactForEveryShDegree) {
  const fs::path dir = scratch_dir("ply_round_trip");
  for (int degree = 0; degree <= 3; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    // Degree 3 with 10000 Gaussians spans several parallel tasks and row tiles of the reader.
    const GaussianPly g = random_ply(degree == 3 ? 10000 : 500, degree, degree % 2 == 1, 100 + degree);
    const fs::path a = dir / "a.ply", b = dir / "b.ply";
    write_ply(a, g);
    const GaussianPly r = read_ply(a);
    expect_identical(g, r);
    write_ply(b, r);
    EXPECT_EQ(file_bytes(a), file_bytes(b)) << "write -> read -> write changed the bytes";
  }
}

TEST(Ply, EmptySceneRoundTrips) {
  const fs::path p = scratch_dir("ply_empty") / "empty.ply";
  GaussianPly g;
  g.sh_degree = 2;
  g.extras.emplace_back("label", std::vector<float>());
  write_ply(p, g);
  const GaussianPly r = read_ply(p);
  EXPECT_EQ(r.count, 0u);
  EXPECT_EQ(r.sh_degree, 2);
  ASSERT_EQ(r.extras.size(), 1u);
  EXPECT_EQ(r.extras[0].first, "label");
}

TEST(Ply, WrittenHeaderFollowsTheStandard3dgsLayout) {
  const fs::path p = scratch_dir("ply_header") / "scene.ply";
  const GaussianPly g = random_ply(7, 3, true, 5);
  write_ply(p, g);
  const std::string bytes = file_bytes(p);
  const size_t end = bytes.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  std::vector<std::string> lines;
  for (std::string line; std::getline(header, line);) lines.push_back(line);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0], "ply");
  EXPECT_EQ(lines[1], "format binary_little_endian 1.0");
  EXPECT_EQ(lines[2], "element vertex 7");
  std::vector<std::string> expected = standard_names(3);
  for (const auto& e : g.extras) expected.push_back(e.first);
  ASSERT_EQ(lines.size(), 3 + expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(lines[3 + i], "property float " + expected[i]);
  // Nothing but the rows follows the header: 62 standard floats + 9 extras per Gaussian.
  EXPECT_EQ(bytes.size(), end + std::string("end_header\n").size() + 7 * (62 + 9) * sizeof(float));
  // Row 0 starts with x, y, z, nx, ny, nz, f_dc, then f_rest channel-major exactly as stored.
  const char* row = bytes.data() + end + 11;
  float first[9 + 45];
  std::memcpy(first, row, sizeof first);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(std::bit_cast<uint32_t>(first[k]), std::bit_cast<uint32_t>(g.positions[k]));
  for (int k = 0; k < 45; ++k) EXPECT_EQ(std::bit_cast<uint32_t>(first[9 + k]), std::bit_cast<uint32_t>(g.f_rest[k]));
}

TEST(Ply, WriteReplacesTheFileAndLeavesNothingElseBehind) {
  const fs::path dir = scratch_dir("ply_replace");
  const fs::path p = dir / "scene.ply";
  write_ply(p, random_ply(20, 1, false, 1));
  const GaussianPly second = random_ply(30, 2, true, 2);
  write_ply(p, second);
  expect_identical(second, read_ply(p));
  auto files_in_dir = [&] { return std::distance(fs::directory_iterator(dir), fs::directory_iterator()); };
  EXPECT_EQ(files_in_dir(), 1) << "a temporary file was left in the folder";

  // A rejected write leaves the previous file as it was.
  const std::string before = file_bytes(p);
  GaussianPly broken = second;
  broken.opacity.pop_back();
  const std::string msg = error_of([&] { write_ply(p, broken); });
  expect_mentions(msg, {p.string(), "opacity"});
  EXPECT_EQ(file_bytes(p), before);
  EXPECT_EQ(files_in_dir(), 1);
}

TEST(Ply, WriteRejectsInconsistentScenes) {
  const fs::path dir = scratch_dir("ply_write_bad");
  const fs::path p = dir / "out.ply";
  const GaussianPly good = random_ply(4, 1, true, 3);
  auto expect_write_error = [&](GaussianPly g, std::initializer_list<std::string> parts) {
    const std::string msg = error_of([&] { write_ply(p, g); });
    expect_mentions(msg, {p.string()});
    expect_mentions(msg, parts);
    EXPECT_FALSE(fs::exists(p));
  };
  GaussianPly g = good;
  g.f_rest.resize(4 * 24);  // degree 2 worth of coefficients for a degree-1 scene
  expect_write_error(g, {"f_rest"});
  g = good;
  g.sh_degree = 4;
  expect_write_error(g, {"SH degree 4"});
  g = good;
  g.extras[1].first = "diffuse_0";
  expect_write_error(g, {"diffuse_0", "twice"});
  g = good;
  g.extras[0].first = "scale_0";
  expect_write_error(g, {"scale_0", "standard"});
  g = good;
  g.extras[0].first = "two words";
  expect_write_error(g, {"two words"});
  g = good;
  g.extras[2].second.push_back(1.0f);
  expect_write_error(g, {"diffuse_2"});
  const std::string msg = error_of([&] { write_ply(dir / "no_such_folder" / "x.ply", good); });
  expect_mentions(msg, {"no_such_folder", "does not exist"});
}

TEST(Ply, MissingNormalsAreWrittenAsZeros) {
  const fs::path p = scratch_dir("ply_no_normals") / "n.ply";
  GaussianPly g = random_ply(5, 0, false, 9);
  g.normals.clear();
  write_ply(p, g);
  const GaussianPly r = read_ply(p);
  EXPECT_EQ(r.normals, std::vector<float>(15, 0.0f));
  EXPECT_TRUE(same_bits(r.positions, g.positions));
}

TEST(Ply, ShLayoutConversionMatchesTheEngineLayout) {
  GaussianPly g = random_ply(3, 2, false, 11);  // K = 9: 8 rest coefficients per channel
  const std::vector<float> sh = sh_to_engine_layout(g);
  ASSERT_EQ(sh.size(), 3u * 16 * 3);
  for (size_t i = 0; i < 3; ++i)
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(sh[i * 48 + c], g.f_dc[i * 3 + c]);
      for (size_t k = 1; k < 9; ++k) EXPECT_EQ(sh[i * 48 + k * 3 + c], g.f_rest[i * 24 + c * 8 + (k - 1)]);
      for (size_t k = 9; k < 16; ++k) EXPECT_EQ(sh[i * 48 + k * 3 + c], 0.0f);
    }
  GaussianPly back;
  back.count = 3;
  back.sh_degree = 2;
  sh_from_engine_layout(sh, back);
  EXPECT_TRUE(same_bits(back.f_dc, g.f_dc));
  EXPECT_TRUE(same_bits(back.f_rest, g.f_rest));
  back.sh_degree = 0;  // lowering the degree drops the higher coefficients
  sh_from_engine_layout(sh, back);
  EXPECT_TRUE(back.f_rest.empty());
  EXPECT_TRUE(same_bits(back.f_dc, g.f_dc));
  EXPECT_FALSE(error_of([&] { sh_from_engine_layout(std::span<const float>(sh).first(10), back); }).empty());
}

// --- files written by other software ----------------------------------------------------------------

TEST(Ply, ReadsAsciiWithAnyPropertyOrderTypesCommentsAndFaces) {
  const fs::path p = scratch_dir("ply_ascii") / "hand.ply";
  write_bytes(p,
              "ply\r\n"
              "format ascii 1.0\r\n"
              "comment written by hand, properties shuffled\r\n"
              "element vertex 2\r\n"
              "property double opacity\r\n"
              "property float z\r\n"
              "property uchar label\r\n"
              "property float y\r\n"
              "property float x\r\n"
              "property float rot_3\r\nproperty float rot_2\r\nproperty float rot_1\r\nproperty float rot_0\r\n"
              "property short f_dc_0\r\nproperty int f_dc_1\r\nproperty float32 f_dc_2\r\n"
              "property float scale_0\r\nproperty float scale_1\r\nproperty float scale_2\r\n"
              "property float roughness\r\n"
              "element face 1\r\n"
              "property list uchar int vertex_indices\r\n"
              "end_header\r\n"
              "-2.5 3 7 2 1 0.25 0.5 0.75 1 -4 12 +0.125 -1 -2 -3 0.5\r\n"
              "1e-3 -3.5e2 255 0 -0 0 0 0 1 0 -1 1e-40 0 0 0 1\r\n"
              "3 0 1 1\r\n");
  const GaussianPly g = read_ply(p);
  ASSERT_EQ(g.count, 2u);
  EXPECT_EQ(g.sh_degree, 0);
  EXPECT_EQ(g.positions, (std::vector<float>{1, 2, 3, -0.0f, 0, -350}));
  EXPECT_TRUE(std::signbit(g.positions[3]));
  EXPECT_EQ(g.rotations, (std::vector<float>{1, 0.75f, 0.5f, 0.25f, 1, 0, 0, 0}));
  EXPECT_EQ(g.f_dc, (std::vector<float>{-4, 12, 0.125f, 0, -1, 1e-40f}));
  EXPECT_EQ(g.opacity, (std::vector<float>{-2.5f, 1e-3f}));
  EXPECT_EQ(g.scales, (std::vector<float>{-1, -2, -3, 0, 0, 0}));
  EXPECT_EQ(g.normals, std::vector<float>(6, 0.0f));
  ASSERT_EQ(g.extras.size(), 2u);
  EXPECT_EQ(g.extras[0].first, "label");  // file order
  EXPECT_EQ(g.extras[0].second, (std::vector<float>{7, 255}));
  EXPECT_EQ(g.extras[1].first, "roughness");
  EXPECT_EQ(g.extras[1].second, (std::vector<float>{0.5f, 1}));
}

TEST(Ply, AsciiWithShortestDecimalsReadsBackBitExact) {
  const GaussianPly g = random_ply(60, 1, true, 21);
  std::vector<std::string> names = standard_names(1);
  for (const auto& e : g.extras) names.push_back(e.first);
  std::string text = float_header("ascii", g.count, names);
  auto put = [&](float f) {
    char b[64];
    const auto r = std::to_chars(b, b + sizeof b, f);
    text.append(b, r.ptr).push_back(' ');
  };
  for (size_t i = 0; i < g.count; ++i) {
    for (int k = 0; k < 3; ++k) put(g.positions[i * 3 + k]);
    for (int k = 0; k < 3; ++k) put(g.normals[i * 3 + k]);
    for (int k = 0; k < 3; ++k) put(g.f_dc[i * 3 + k]);
    for (int k = 0; k < 9; ++k) put(g.f_rest[i * 9 + k]);
    put(g.opacity[i]);
    for (int k = 0; k < 3; ++k) put(g.scales[i * 3 + k]);
    for (int k = 0; k < 4; ++k) put(g.rotations[i * 4 + k]);
    for (const auto& e : g.extras) put(e.second[i]);
    text += "\n";
  }
  const fs::path p = scratch_dir("ply_ascii_exact") / "a.ply";
  write_bytes(p, text);
  expect_identical(g, read_ply(p));
}

TEST(Ply, ReadsBinaryWithOtherTypesOrderAndElements) {
  // A camera element (fixed size) and a list element before the vertices, a face element after them.
  std::string f =
      "ply\nformat binary_little_endian 1.0\n"
      "element camera 2\nproperty float a\nproperty uchar b\n"
      "element meta 2\nproperty list uchar float values\nproperty int tag\n"
      "element vertex 2\n"
      "property double z\nproperty float y\nproperty short x\n"
      "property uchar f_dc_0\nproperty char f_dc_1\nproperty ushort f_dc_2\n"
      "property int opacity\nproperty uint scale_0\nproperty float64 scale_1\nproperty float32 scale_2\n"
      "property int8 rot_0\nproperty uint8 rot_1\nproperty int16 rot_2\nproperty uint16 rot_3\n"
      "property int32 label\nproperty uint32 region\n"
      "property float nz\nproperty float ny\nproperty float nx\n"
      "element face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n";
  for (int i = 0; i < 2; ++i) append<float>(f, 9.0f), append<uint8_t>(f, 9);
  append<uint8_t>(f, 2), append<float>(f, 1.0f), append<float>(f, 2.0f), append<int32_t>(f, 5);
  append<uint8_t>(f, 0), append<int32_t>(f, 6);
  for (int i = 0; i < 2; ++i) {
    append<double>(f, 0.1 + i);
    append<float>(f, -2.0f - i);
    append<int16_t>(f, int16_t(-300 - i));
    append<uint8_t>(f, uint8_t(200 + i));
    append<int8_t>(f, int8_t(-100 - i));
    append<uint16_t>(f, uint16_t(60000 + i));
    append<int32_t>(f, -70000 - i);
    append<uint32_t>(f, 4000000000u + i);
    append<double>(f, -1e-5 * (i + 1));
    append<float>(f, 0.5f + i);
    append<int8_t>(f, -1), append<uint8_t>(f, 2), append<int16_t>(f, -3), append<uint16_t>(f, 4);
    append<int32_t>(f, 7 + i), append<uint32_t>(f, 8u + i);
    append<float>(f, 1.0f), append<float>(f, 0.0f), append<float>(f, -1.0f);
  }
  append<uint8_t>(f, 3), append<int32_t>(f, 0), append<int32_t>(f, 1), append<int32_t>(f, 1);
  const fs::path p = scratch_dir("ply_types") / "types.ply";
  write_bytes(p, f);
  const GaussianPly g = read_ply(p);
  ASSERT_EQ(g.count, 2u);
  EXPECT_EQ(g.positions, (std::vector<float>{-300, -2, 0.1f, -301, -3, 1.1f}));
  EXPECT_EQ(g.f_dc, (std::vector<float>{200, -100, 60000, 201, -101, 60001}));
  EXPECT_EQ(g.opacity, (std::vector<float>{-70000, -70001}));
  EXPECT_EQ(g.scales, (std::vector<float>{4e9f, float(-1e-5), 0.5f, float(4000000001u), float(-2e-5), 1.5f}));
  EXPECT_EQ(g.rotations, (std::vector<float>{-1, 2, -3, 4, -1, 2, -3, 4}));
  EXPECT_EQ(g.normals, (std::vector<float>{-1, 0, 1, -1, 0, 1}));
  ASSERT_EQ(g.extras.size(), 2u);
  EXPECT_EQ(g.extras[0].first, "label");
  EXPECT_EQ(g.extras[0].second, (std::vector<float>{7, 8}));
  EXPECT_EQ(g.extras[1].first, "region");
  EXPECT_EQ(g.extras[1].second, (std::vector<float>{8, 9}));
}

TEST(Ply, ParsesFromMemoryWithTheGivenName) {
  const fs::path p = scratch_dir("ply_memory") / "m.ply";
  const GaussianPly g = random_ply(9, 3, true, 4);
  write_ply(p, g);
  const std::string bytes = file_bytes(p);
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  expect_identical(g, parse_ply(data, bytes.size(), "memory"));
  const std::string msg = error_of([&] { parse_ply(data, 100, "in-memory scene"); });
  expect_mentions(msg, {"in-memory scene:"});
}

// --- bad input --------------------------------------------------------------------------------------

TEST(Ply, MissingFileOrFolder) {
  const fs::path dir = scratch_dir("ply_missing");
  expect_mentions(error_of([&] { read_ply(dir / "nope.ply"); }), {(dir / "nope.ply").string(), "not found"});
  expect_mentions(error_of([&] { read_ply(dir); }), {dir.string(), "folder"});
  expect_mentions(error_of([&] { ply_summary(dir / "nope.ply"); }), {(dir / "nope.ply").string(), "not found"});
}

TEST(Ply, RejectsFilesThatAreNotPly) {
  const fs::path dir = scratch_dir("ply_not_ply");
  expect_read_error(dir, "empty.ply", "", {"empty"});
  expect_read_error(dir, "text.ply", "hello world\nmore\n", {"not a PLY file"});
  expect_read_error(dir, "no_newline.ply", "ply", {"not a PLY file"});
  expect_read_error(dir, "no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", {"end_header"});
  expect_read_error(dir, "no_format.ply", "ply\nelement vertex 0\nend_header\n", {"no format line"});
  expect_read_error(dir, "bad_format.ply", "ply\nformat binary 1.0\nend_header\n", {"unknown PLY format", "'binary'"});
  expect_read_error(dir, "bad_version.ply", "ply\nformat ascii 2.0\nend_header\n", {"version", "2.0"});
  expect_read_error(dir, "keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 1\nend_header\n",
                    {"line 3", "unknown header keyword 'elemnt'"});
  expect_read_error(dir, "count.ply", "ply\nformat ascii 1.0\nelement vertex -5\nend_header\n", {"invalid count '-5'"});
  expect_read_error(dir, "orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", {"before any element"});
  expect_read_error(dir, "no_vertex.ply",
                    "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int i\nend_header\n",
                    {"no 'vertex' element"});
}

TEST(Ply, RejectsBigEndian) {
  expect_read_error(scratch_dir("ply_big_endian"), "be.ply",
                    float_header("binary_big_endian", 1, standard_names(0)) + std::string(62 * 4, '\0'),
                    {"binary_big_endian", "not supported"});
}

TEST(Ply, RejectsMissingRequiredPropertiesByName) {
  const fs::path dir = scratch_dir("ply_missing_property");
  for (const std::string drop : {"x", "z", "f_dc_1", "opacity", "scale_2", "rot_0", "rot_3"}) {
    std::vector<std::string> names;
    for (const auto& n : standard_names(0))
      if (n != drop) names.push_back(n);
    expect_read_error(dir, "no_" + drop + ".ply", float_header("ascii", 0, names), {"missing", "'" + drop + "'"});
  }
  std::vector<std::string> names = standard_names(0);
  names.erase(names.begin() + 4);  // ny
  expect_read_error(dir, "half_normals.ply", float_header("ascii", 0, names), {"normals", "'ny'"});
}

TEST(Ply, RejectsShCountsThatAreNoDegree) {
  const fs::path dir = scratch_dir("ply_sh_count");
  std::vector<std::string> names = standard_names(1);
  names.push_back("f_rest_9");  // 10 coefficients
  expect_read_error(dir, "ten.ply", float_header("ascii", 0, names), {"10 f_rest", "0, 9, 24 or 45"});
  names = standard_names(1);
  names[9 + 4] = "f_rest_12";  // 9 coefficients, but one is numbered past the end
  expect_read_error(dir, "gap.ply", float_header("ascii", 0, names), {"f_rest_12", "not numbered"});
}

TEST(Ply, RejectsUnknownTypesAndListsInVertices) {
  const fs::path dir = scratch_dir("ply_types_bad");
  std::string h = float_header("binary_little_endian", 0, standard_names(0));
  std::string bad = h;
  bad.replace(bad.find("property float opacity"), 22, "property half opacity");
  expect_read_error(dir, "half.ply", bad, {"'opacity'", "unknown type 'half'"});
  bad = h;
  bad.replace(bad.find("end_header"), 10, "property list uchar int idx\nend_header");
  expect_read_error(dir, "list.ply", bad, {"'idx'", "list"});
  bad = h;
  bad.replace(bad.find("end_header"), 10, "element face 1\nproperty list float int idx\nend_header");
  expect_read_error(dir, "list_count.ply", bad, {"'idx'", "non-integer count type 'float'"});
  bad = h;
  bad.replace(bad.find("end_header"), 10, "element face 1\nproperty list uchar quad idx\nend_header");
  expect_read_error(dir, "list_item.ply", bad, {"'idx'", "unknown item type 'quad'"});
  bad = h;
  bad.replace(bad.find("end_header"), 10, "property float x\nend_header");
  expect_read_error(dir, "twice.ply", bad, {"'x'", "declared twice"});
  bad = h;
  bad.replace(bad.find("end_header"), 10, std::string("property float la\x01\0bel\nend_header", 33));
  expect_read_error(dir, "control.ply", bad, {"control or non-ASCII characters", "'property float la??bel'"});
}

TEST(Ply, RejectsTruncatedData) {
  const fs::path dir = scratch_dir("ply_truncated");
  const fs::path good = dir / "good.ply";
  write_ply(good, random_ply(10, 3, false, 8));
  const std::string bytes = file_bytes(good);
  expect_read_error(dir, "short.ply", bytes.substr(0, bytes.size() - 1),
                    {"truncated", "10 vertices", "248 bytes", std::to_string(10 * 248 - 1) + " bytes"});
  expect_read_error(dir, "header_only.ply", bytes.substr(0, bytes.find("end_header") + 11),
                    {"truncated", "10 vertices", "only 0 bytes"});
  // ASCII: too little text for the declared count, and text that ends in the middle of a vertex.
  const std::string h = float_header("ascii", 3, standard_names(0));
  std::string row;
  for (int k = 0; k < 17; ++k) row += "1 ";
  expect_read_error(dir, "ascii_short.ply", h + row + "\n", {"truncated", "3 vertices"});
  expect_read_error(dir, "ascii_mid.ply", h + row + "\n" + row + "\n" + row.substr(0, 20) + std::string(30, ' '),
                    {"truncated", "3 vertices", "vertex 2", "120 bytes"});
  // An element before the vertices that runs past the end of the file.
  expect_read_error(dir, "before.ply",
                    "ply\nformat binary_little_endian 1.0\nelement meta 1\nproperty list uchar float v\n" +
                        float_header("binary_little_endian", 0, standard_names(0)).substr(36) + "\x05",
                    {"truncated", "'meta'"});
}

TEST(Ply, RejectsBadValues) {
  const fs::path dir = scratch_dir("ply_values");
  const std::string h = float_header("ascii", 1, standard_names(0));
  std::string row;
  for (int k = 0; k < 17; ++k) row += (k == 9 ? "0.5x " : "1 ");
  expect_read_error(dir, "word.ply", h + row, {"vertex 0", "'opacity'", "'0.5x'"});
  row.clear();
  for (int k = 0; k < 17; ++k) row += (k == 2 ? "nan " : "1 ");
  expect_read_error(dir, "nan_ascii.ply", h + row, {"vertex 0", "'z'", "not a finite"});
  std::string uh = h;
  uh.replace(uh.find("property float opacity"), 22, "property uchar opacity");
  row.clear();
  for (int k = 0; k < 17; ++k) row += (k == 9 ? "256 " : "1 ");
  expect_read_error(dir, "uchar_range.ply", uh + row, {"'opacity'", "uchar", "'256'"});

  // Binary: an infinite float, and a double beyond float range.
  GaussianPly g = random_ply(5, 0, false, 2);
  const fs::path ok = dir / "ok.ply";
  write_ply(ok, g);
  std::string bytes = file_bytes(ok);
  const size_t data = bytes.find("end_header\n") + 11;
  std::string inf = bytes;
  const float infinity = std::numeric_limits<float>::infinity();
  std::memcpy(&inf[data + (3 * 17 + 11) * 4], &infinity, 4);  // vertex 3, scale_1
  expect_read_error(dir, "inf.ply", inf, {"vertex 3", "'scale_1'", "not a finite"});
  const fs::path big = dir / "big.ply";
  write_ply(big, random_ply(5000, 0, false, 3));  // several parallel tasks: the index must still be exact
  std::string late = file_bytes(big);
  std::memcpy(&late[late.find("end_header\n") + 11 + (4321 * 17 + 14) * 4], &infinity, 4);
  expect_read_error(dir, "late_inf.ply", late, {"vertex 4321", "'rot_1'", "not a finite"});
  std::string dh = float_header("binary_little_endian", 1, standard_names(0));
  dh.replace(dh.find("property float rot_2"), 20, "property double rot_2");
  std::string drow;
  for (int k = 0; k < 17; ++k) k == 15 ? append<double>(drow, 1e300) : append<float>(drow, 1.0f);
  expect_read_error(dir, "double_range.ply", dh + drow, {"vertex 0", "'rot_2'", "out of float range"});
}

TEST(Ply, InfiniteOpacityIsFullyOpaqueOrTransparent) {
  // splat-transform writes an SPZ opacity byte of 255 as +inf in a PLY: read as the logit our own 8-bit
  // decoders give alpha 1 (and -inf as alpha 0); a NaN opacity stays an error.
  const fs::path dir = scratch_dir("ply_inf_opacity");
  const float limit = std::log(509.0f);  // alpha 1 - 0.5/255, half a byte step inside 1
  GaussianPly g = random_ply(3, 0, false, 4);
  const fs::path ok = dir / "ok.ply";
  write_ply(ok, g);
  std::string bytes = file_bytes(ok);
  const size_t data = bytes.find("end_header\n") + 11;
  const float inf = std::numeric_limits<float>::infinity(), minus_inf = -inf;
  std::memcpy(&bytes[data + (0 * 17 + 9) * 4], &inf, 4);        // vertex 0, opacity
  std::memcpy(&bytes[data + (2 * 17 + 9) * 4], &minus_inf, 4);  // vertex 2, opacity
  const fs::path binary = dir / "binary.ply";
  std::ofstream(binary, std::ios::binary) << bytes;
  const GaussianPly b = read_ply(binary);
  EXPECT_NEAR(b.opacity[0], limit, 1e-4f);
  EXPECT_EQ(b.opacity[1], g.opacity[1]);
  EXPECT_NEAR(b.opacity[2], -limit, 1e-4f);

  const std::string h = float_header("ascii", 2, standard_names(0));
  std::string rows;
  for (const char* o : {"inf", "-inf"}) {
    for (int k = 0; k < 17; ++k) rows += k == 9 ? std::string(o) + " " : "1 ";
    rows += "\n";
  }
  const fs::path ascii = dir / "ascii.ply";
  std::ofstream(ascii, std::ios::binary) << h + rows;
  const GaussianPly a = read_ply(ascii);
  EXPECT_NEAR(a.opacity[0], limit, 1e-4f);
  EXPECT_NEAR(a.opacity[1], -limit, 1e-4f);

  std::string row;
  for (int k = 0; k < 17; ++k) row += (k == 9 ? "nan " : "1 ");
  expect_read_error(dir, "nan_opacity.ply", float_header("ascii", 1, standard_names(0)) + row,
                    {"vertex 0", "'opacity'", "not a finite"});
}

// --- summary -----------------------------------------------------------------------------------------

TEST(Ply, SummaryNamesCountDegreeExtrasBoundsAndOpacity) {
  const fs::path p = scratch_dir("ply_summary") / "s.ply";
  GaussianPly g = random_ply(4, 2, true, 6);
  g.positions = {0, 0, 0, 1, 2, 3, -1, 5, 0.5f, 0.25f, -2, 1};
  g.opacity = {0, 0, 0, 0};
  write_ply(p, g);
  const std::string s = ply_summary(p);
  expect_mentions(s, {p.string(), "binary_little_endian", "4 Gaussians", "SH degree 2", "extra properties (9)",
                      "diffuse_0", "label", "x [-1, 1]", "y [-2, 5]", "z [0, 3]", "min 0.5", "max 0.5"});
}

// --- the external fixture -----------------------------------------------------------------------------

double rel_err(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-3); }

TEST(Ply, GardenFixtureMatchesItsNpyArraysAfterActivation) {
  GORIS_REQUIRE_SHARED("fixtures/rasterizer_garden");
  const fs::path dir = test::shared_dir() / "fixtures/rasterizer_garden";
  const GaussianPly g = read_ply(dir / "gaussians.ply");
  ASSERT_EQ(g.count, 8000u);
  ASSERT_EQ(g.sh_degree, 3);
  const NpyArray means = load_npy(dir / "means.npy"), scales = load_npy(dir / "scales.npy"),
                 quats = load_npy(dir / "quats_wxyz.npy"), opac = load_npy(dir / "opacities.npy"),
                 sh = load_npy(dir / "sh.npy");
  ASSERT_EQ(means.shape, (std::vector<size_t>{8000, 3}));
  ASSERT_EQ(sh.shape, (std::vector<size_t>{8000, 16, 3}));
  const std::vector<float> engine_sh = sh_to_engine_layout(g);
  double worst = 0;
  for (size_t i = 0; i < g.count; ++i) {
    double qn = 0;
    for (int k = 0; k < 4; ++k) qn += double(g.rotations[i * 4 + k]) * g.rotations[i * 4 + k];
    qn = std::sqrt(qn);
    for (int k = 0; k < 4; ++k) worst = std::max(worst, rel_err(g.rotations[i * 4 + k] / qn, quats.data[i * 4 + k]));
    for (int k = 0; k < 3; ++k) {
      worst = std::max(worst, rel_err(g.positions[i * 3 + k], means.data[i * 3 + k]));
      worst = std::max(worst, rel_err(std::exp(double(g.scales[i * 3 + k])), scales.data[i * 3 + k]));
      worst = std::max(worst, rel_err(g.f_dc[i * 3 + k], sh.data[i * 48 + k]));
    }
    worst = std::max(worst, rel_err(1.0 / (1.0 + std::exp(-double(g.opacity[i]))), opac.data[i]));
    for (int j = 0; j < 48; ++j) worst = std::max(worst, rel_err(engine_sh[i * 48 + j], sh.data[i * 48 + j]));
  }
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace goris
