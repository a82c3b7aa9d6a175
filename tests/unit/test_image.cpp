#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "core/io/image.h"
#include "tests/support/test_support.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
namespace fs = std::filesystem;
using test::expect_error;

Image gradient(int w, int h, int c) {
  Image im(w, h, c);
  for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = float(i % 256) / 255.0f;
  return im;
}

TEST(Image, Png8BitRoundTripIsExactOnTheGrid) {
  const auto dir = test::scratch_dir("image_png8");
  for (int c : {1, 3, 4}) {
    const Image im = gradient(7, 5, c);
    save_png(dir / "a.png", im);
    const Image back = read_image(dir / "a.png");
    ASSERT_EQ(back.width, 7);
    ASSERT_EQ(back.height, 5);
    ASSERT_EQ(back.channels, c);
    for (size_t i = 0; i < im.pixels.size(); ++i) ASSERT_FLOAT_EQ(back.pixels[i], im.pixels[i]) << "c=" << c << " i=" << i;
  }
}

TEST(Image, Png16BitKeepsPrecision) {
  const auto dir = test::scratch_dir("image_png16");
  Image im(3, 2, 3);
  for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = float(1000 + 3001 * i) / 65535.0f;
  save_png(dir / "a.png", im, /*sixteen_bit=*/true);
  const cv::Mat raw = cv::imread((dir / "a.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(raw.depth(), CV_16U);
  const Image back = read_image(dir / "a.png");
  for (size_t i = 0; i < im.pixels.size(); ++i) EXPECT_NEAR(back.pixels[i], im.pixels[i], 1e-7);
}

TEST(Image, ChannelOrderIsRgbOnDisk) {
  const auto dir = test::scratch_dir("image_rgb");
  Image im(1, 1, 3);
  im.pixels[0] = 1.0f, im.pixels[1] = 0.0f, im.pixels[2] = 0.0f;  // red
  save_png(dir / "red.png", im);
  const cv::Mat raw = cv::imread((dir / "red.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(raw.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 255));  // OpenCV's BGR
  const Image back = read_image(dir / "red.png");
  EXPECT_EQ(back.pixels[0], 1.0f);
  EXPECT_EQ(back.pixels[2], 0.0f);
}

TEST(Image, RgbaIsCompositedOnTheBackground) {
  const auto dir = test::scratch_dir("image_rgba");
  Image im(2, 1, 4);
  const float px[8] = {1, 0, 0, 1, /* opaque red */ 0, 1, 0, 0.2f /* mostly transparent green */};
  for (int i = 0; i < 8; ++i) im.pixels[i] = px[i];
  save_png(dir / "a.png", im, true);
  const Image black = load_image(dir / "a.png", Device::CPU);
  ASSERT_EQ(black.channels, 3);
  EXPECT_NEAR(black.pixels[0], 1.0f, 1e-6);
  EXPECT_NEAR(black.pixels[4], 0.2f, 1e-4);
  const Image white = load_image(dir / "a.png", Device::CPU, glm::vec3(1.0f));
  EXPECT_NEAR(white.pixels[3], 0.8f, 1e-4);  // R of the green pixel: 0 * 0.2 + 1 * 0.8
  EXPECT_NEAR(white.pixels[4], 1.0f, 1e-4);
  EXPECT_NEAR(white.pixels[1], 0.0f, 1e-6);  // opaque pixel ignores the background
}

TEST(Image, AlphaComesFromRgbaImagesOnly) {
  const auto dir = test::scratch_dir("image_alpha");
  Image rgba(2, 1, 4);
  const float px[8] = {1, 0, 0, 1, 0, 1, 0, 0.2f};
  for (int i = 0; i < 8; ++i) rgba.pixels[i] = px[i];
  save_png(dir / "a.png", rgba, true);
  const std::optional<Image> a = load_alpha(dir / "a.png");
  ASSERT_TRUE(a.has_value());
  ASSERT_EQ(a->channels, 1);
  EXPECT_NEAR(a->pixels[0], 1.0f, 1e-6);
  EXPECT_NEAR(a->pixels[1], 0.2f, 1e-4);
  Image rgb(2, 1, 3);
  for (int i = 0; i < 6; ++i) rgb.pixels[i] = 0.5f;
  save_png(dir / "b.png", rgb);
  EXPECT_FALSE(load_alpha(dir / "b.png").has_value());
  test::expect_error([&] { load_alpha(dir / "missing.png"); }, "missing.png");
}

TEST(Image, GreyExpandsToRgbAndMasksAreOneChannel) {
  const auto dir = test::scratch_dir("image_grey");
  test::write_png(dir / "g.png", 4, 3, 1, 0.6f);
  const Image rgb = load_image(dir / "g.png", Device::CPU);
  EXPECT_EQ(rgb.channels, 3);
  EXPECT_NEAR(rgb.pixels[5], 0.6f, 1.0 / 255);
  // Colour mask: the largest channel, times alpha.
  Image m(1, 1, 4);
  m.pixels[0] = 0.2f, m.pixels[1] = 1.0f, m.pixels[2] = 0.0f, m.pixels[3] = 0.5f;
  save_png(dir / "m.png", m, true);
  const Image mask = load_mask(dir / "m.png");
  EXPECT_EQ(mask.channels, 1);
  EXPECT_NEAR(mask.pixels[0], 0.5f, 1e-4);
}

TEST(Image, AreaDownscaleAverages) {
  Image im(4, 2, 1);
  const float v[8] = {0, 1, 0.5f, 0.5f, 1, 0, 0.25f, 0.75f};
  for (int i = 0; i < 8; ++i) im.pixels[i] = v[i];
  const Image small = resize_image(im, 2, 1);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_NEAR(small.pixels[0], 0.5f, 1e-6);
  EXPECT_NEAR(small.pixels[1], 0.5f, 1e-6);
  const Image same = resize_image(im, 4, 2);
  EXPECT_EQ(same.pixels[7], 0.75f);
  expect_error([&] { resize_image(im, 0, 3); }, {"invalid target size"});
}

TEST(Image, ProbeReadsHeadersOnly) {
  const auto dir = test::scratch_dir("image_probe");
  test::write_png(dir / "a.png", 37, 21);
  EXPECT_EQ(probe_image_size(dir / "a.png"), (ImageSize{37, 21}));
  cv::Mat jpg(13, 29, CV_8UC3, cv::Scalar(10, 20, 30));
  ASSERT_TRUE(cv::imwrite((dir / "b.jpg").string(), jpg));
  EXPECT_EQ(probe_image_size(dir / "b.jpg"), (ImageSize{29, 13}));
  ASSERT_TRUE(cv::imwrite((dir / "c.bmp").string(), jpg));  // no header parser: decoded once
  EXPECT_EQ(probe_image_size(dir / "c.bmp"), (ImageSize{29, 13}));
  // A PNG cut after the signature, a JPEG without a frame header.
  test::write_bytes(dir / "cut.png", {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0});
  expect_error([&] { probe_image_size(dir / "cut.png"); }, {"cut.png", "truncated PNG"});
  test::write_bytes(dir / "cut.jpg", {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10, 'J', 'F'});
  expect_error([&] { probe_image_size(dir / "cut.jpg"); }, {"cut.jpg", "JPEG"});
  expect_error([&] { probe_image_size(dir / "none.png"); }, {"none.png", "not found"});
  expect_error([&] { probe_image_size(dir); }, {"image_probe", "folder"});
}

TEST(Image, BadFilesNameTheFile) {
  const auto dir = test::scratch_dir("image_bad");
  expect_error([&] { load_image(dir / "missing.png", Device::CPU); }, {"missing.png", "not found"});
  test::write_text(dir / "junk.png", "this is not an image");
  expect_error([&] { load_image(dir / "junk.png", Device::CPU); }, {"junk.png", "cannot decode"});
  expect_error([&] { load_mask(dir / "junk.png"); }, {"junk.png", "cannot decode"});
}

TEST(Image, SaveGoesThroughATemporaryFile) {
  const auto dir = test::scratch_dir("image_save");
  test::write_png(dir / "keep.png", 2, 2, 3, 0.25f);
  Image two_channels(2, 2, 2);
  expect_error([&] { save_png(dir / "keep.png", two_channels); }, {"keep.png", "2 channels"});
  EXPECT_NEAR(read_image(dir / "keep.png").pixels[0], 0.25f, 1.0 / 255);  // untouched
  expect_error([&] { save_png(dir / "no_such_folder" / "a.png", two_channels); }, {"a.png"});
  Image ok(2, 2, 3);
  ok.pixels.fill_zero();
  expect_error([&] { save_png(dir / "no_such_folder" / "a.png", ok); }, {"a.png", "does not exist"});
  save_png(dir / "keep.png", ok);
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left behind
  EXPECT_EQ(read_image(dir / "keep.png").pixels[0], 0.0f);
}

TEST(Image, SaveClampsOutOfRangeAndNaN) {
  const auto dir = test::scratch_dir("image_clamp");
  Image im(3, 1, 1);
  im.pixels[0] = -1.0f, im.pixels[1] = 2.0f, im.pixels[2] = std::numeric_limits<float>::quiet_NaN();
  save_png(dir / "a.png", im);
  const Image back = read_image(dir / "a.png");
  EXPECT_EQ(back.pixels[0], 0.0f);
  EXPECT_EQ(back.pixels[1], 1.0f);
  EXPECT_EQ(back.pixels[2], 0.0f);
}

}  // namespace
}  // namespace goris
