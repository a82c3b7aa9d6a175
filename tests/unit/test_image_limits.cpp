// Image files are checked before anything is allocated or opened: a small PNG or JPEG whose header declares
// a huge image is refused with its name and size, and a FIFO or device is refused by type instead of
// blocking the reader.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/io/file_bytes.h"
#include "core/io/image.h"
#include "core/io/ply.h"
#include "io_test_util.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {
namespace fs = std::filesystem;

void put_be32(std::vector<uint8_t>& b, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(uint8_t(v >> s));
}

// The PNG signature and an IHDR chunk declaring w x h, nothing after it.
std::vector<uint8_t> png_header(uint32_t w, uint32_t h) {
  std::vector<uint8_t> b = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  put_be32(b, 13);
  for (char c : std::string("IHDR")) b.push_back(uint8_t(c));
  put_be32(b, w);
  put_be32(b, h);
  for (uint8_t x : {8, 6, 0, 0, 0}) b.push_back(x);
  put_be32(b, 0);  // CRC (not checked by the probe)
  return b;
}

// SOI, then a baseline frame header (SOF0) declaring w x h.
std::vector<uint8_t> jpeg_header(uint16_t w, uint16_t h) {
  return {0xFF, 0xD8, 0xFF, 0xC0, 0x00, 0x11, 0x08, uint8_t(h >> 8), uint8_t(h), uint8_t(w >> 8), uint8_t(w), 0x03};
}

TEST(ImageLimits, HugeDeclaredSizeIsRefusedBeforeDecoding) {
  const fs::path dir = test::scratch_dir("image_limits_huge");
  test::write_bytes(dir / "huge.png", png_header(12000, 12000));
  test::expect_error([&] { read_image(dir / "huge.png"); }, (dir / "huge.png").string());
  test::expect_error([&] { read_image(dir / "huge.png"); }, "12000x12000");
  test::expect_error([&] { read_image(dir / "huge.png"); }, "limit of 100 megapixels");
  test::write_bytes(dir / "huge.jpg", jpeg_header(60000, 60000));
  test::expect_error([&] { read_image(dir / "huge.jpg"); }, "60000x60000");
  // The probe itself still reports the size (goris info shows it).
  EXPECT_EQ(probe_image_size(dir / "huge.png").width, 12000);
  // An ordinary image still loads.
  test::write_png(dir / "small.png", 8, 4);
  EXPECT_EQ(read_image(dir / "small.png").width, 8);
}

TEST(ImageLimits, FifoIsRefusedByType) {
  const fs::path dir = test::scratch_dir("image_limits_fifo");
  const fs::path fifo = dir / "scene.ply";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  test::expect_error([&] { read_file_bytes(fifo); }, "is a FIFO (named pipe)");
  test::expect_error([&] { read_image(fifo); }, "FIFO");
  test::expect_error([&] { ply_summary(fifo); }, fifo.string() + ": is a FIFO");
  test::expect_error([&] { read_file_bytes("/dev/null"); }, "character device");
}

}  // namespace
}  // namespace goris
