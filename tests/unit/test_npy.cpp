#include <gtest/gtest.h>

#include <cstring>

#include "core/io/npy.h"
#include "tests/support/test_support.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
using test::expect_error;
using test::npy_bytes;

// Raw little-endian bytes of `values` of type T, wrapped in a .npy with `descr`.
template <class T>
std::vector<uint8_t> typed_npy(const std::string& descr, const std::vector<T>& values) {
  std::vector<uint8_t> b = npy_bytes({values.size()}, {}, descr);
  const size_t at = b.size();
  b.resize(at + values.size() * sizeof(T));
  std::memcpy(b.data() + at, values.data(), values.size() * sizeof(T));
  return b;
}

NpyArray parse(const std::vector<uint8_t>& b) { return parse_npy(b.data(), b.size(), "test.npy"); }

TEST(Npy, ReadsF8MatrixInCOrder) {
  const auto b = npy_bytes({2, 3}, {1, 2, 3, 4, 5, 6.5});
  const NpyArray a = parse(b);
  ASSERT_EQ(a.shape, (std::vector<size_t>{2, 3}));
  EXPECT_DOUBLE_EQ(a.at(0, 2), 3.0);
  EXPECT_DOUBLE_EQ(a.at(1, 2), 6.5);
}

TEST(Npy, ReadsEveryDtype) {
  EXPECT_EQ(parse(typed_npy<float>("<f4", {1.5f, -2.0f})).data, (std::vector<double>{1.5, -2.0}));
  EXPECT_EQ(parse(typed_npy<int32_t>("<i4", {-7, 9})).data, (std::vector<double>{-7, 9}));
  EXPECT_EQ(parse(typed_npy<int64_t>("<i8", {-(int64_t(1) << 40), 3})).data,
            (std::vector<double>{-double(int64_t(1) << 40), 3}));
  EXPECT_EQ(parse(typed_npy<uint8_t>("|u1", {0, 255})).data, (std::vector<double>{0, 255}));
  EXPECT_EQ(parse(typed_npy<uint16_t>("<u2", {65535, 1})).data, (std::vector<double>{65535, 1}));
  EXPECT_EQ(parse(typed_npy<uint32_t>("<u4", {4000000000u})).data, (std::vector<double>{4000000000.0}));
  EXPECT_EQ(parse(typed_npy<uint8_t>("|b1", {0, 1, 2})).data, (std::vector<double>{0, 1, 1}));
}

TEST(Npy, ScalarAndEmptyArrays) {
  const NpyArray s = parse(npy_bytes({}, {42.0}));
  EXPECT_TRUE(s.shape.empty());
  EXPECT_EQ(s.data, (std::vector<double>{42.0}));
  const NpyArray e = parse(npy_bytes({0, 17}, {}));
  EXPECT_EQ(e.shape, (std::vector<size_t>{0, 17}));
  EXPECT_TRUE(e.data.empty());
}

TEST(Npy, Version2Header) {
  auto b = npy_bytes({2}, {1, 2});
  // Re-wrap the v1 header as v2 (4-byte header length).
  const uint16_t len = uint16_t(b[8] | (b[9] << 8));
  std::vector<uint8_t> v2 = {0x93, 'N', 'U', 'M', 'P', 'Y', 2, 0, uint8_t(len & 0xff), uint8_t(len >> 8), 0, 0};
  v2.insert(v2.end(), b.begin() + 10, b.end());
  EXPECT_EQ(parse(v2).data, (std::vector<double>{1, 2}));
}

TEST(Npy, BadInputNamesFileAndProblem) {
  auto good = npy_bytes({2, 2}, {1, 2, 3, 4});
  auto bad_magic = good;
  bad_magic[1] = 'X';
  expect_error([&] { parse(bad_magic); }, {"test.npy", "bad magic"});
  auto bad_version = good;
  bad_version[6] = 9;
  expect_error([&] { parse(bad_version); }, {"test.npy", "version 9"});
  expect_error([&] { parse(std::vector<uint8_t>(good.begin(), good.begin() + 40)); }, {"test.npy", "truncated .npy header"});
  expect_error([&] { parse(std::vector<uint8_t>(good.begin(), good.end() - 1)); }, {"test.npy", "truncated .npy data"});
  auto extra = good;
  extra.push_back(0);
  expect_error([&] { parse(extra); }, {"test.npy", "extra bytes"});
  expect_error([&] { parse(npy_bytes({2}, {1, 2}, "<f8", true)); }, {"test.npy", "Fortran"});
  expect_error([&] { parse(npy_bytes({2}, {1, 2}, ">f8")); }, {"test.npy", "big-endian"});
  expect_error([&] { parse(npy_bytes({1}, {1}, "<c16")); }, {"test.npy", "unsupported .npy dtype '<c16'"});
  expect_error([&] { parse(npy_bytes({1}, {1}, "<U8")); }, {"test.npy", "unsupported"});
}

TEST(Npy, MalformedHeaders) {
  auto with_header = [](std::string h) {
    h += '\n';
    return test::npy_from_header(h, {});
  };
  expect_error([&] { parse(with_header("{'descr': '<f8', 'fortran_order': False}")); }, {"test.npy", "no 'shape'"});
  expect_error([&] { parse(with_header("{'descr': '<f8', 'shape': (1,)}")); }, {"test.npy", "no 'fortran_order'"});
  expect_error([&] { parse(with_header("['descr']")); }, {"test.npy", "malformed .npy header", "'{'"});
  expect_error([&] { parse(with_header("{'descr': '<f8', 'fortran_order': Maybe, 'shape': (1,)}")); },
               {"test.npy", "True or False"});
  expect_error([&] { parse(with_header("{'descr': '<f8', 'fortran_order': False, 'shape': (1, x)}")); },
               {"test.npy", "dimension"});
  expect_error([&] { parse(with_header("{'descr: '<f8'}")); }, {"test.npy", "malformed"});
  expect_error([&] { parse(with_header("{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999, 99999999999, 99999999999)}")); },
               {"test.npy", "too large"});
}

TEST(Npy, LoadNpyFromFile) {
  const auto dir = test::scratch_dir("npy_file");
  test::write_bytes(dir / "a.npy", npy_bytes({3}, {1, 2, 3}));
  EXPECT_EQ(load_npy(dir / "a.npy").data, (std::vector<double>{1, 2, 3}));
  expect_error([&] { load_npy(dir / "missing.npy"); }, {"missing.npy", "not found"});
  test::write_bytes(dir / "short.npy", {0x93, 'N', 'U'});
  expect_error([&] { load_npy(dir / "short.npy"); }, {"short.npy", "bad magic"});
}

TEST(Npy, GoldcapePosesBounds) {
  GORIS_REQUIRE_SHARED("datasets/goldcape/poses_bounds.npy");
  const NpyArray a = load_npy(test::shared_dir() / "datasets/goldcape/poses_bounds.npy");
  ASSERT_EQ(a.shape, (std::vector<size_t>{119, 17}));
  EXPECT_DOUBLE_EQ(a.at(0, 4), 3648.0);  // h of the original photos
  EXPECT_DOUBLE_EQ(a.at(0, 9), 3648.0);  // w
}

}  // namespace
}  // namespace goris
