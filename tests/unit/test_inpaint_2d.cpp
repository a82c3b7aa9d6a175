// 2D inpainting of stage-2 maps: the OpenCV / FSR backends on smooth images, the per-kind encodings
// (depth in inverse depth without "no surface" sources, normals renormalised), the external-program
// hook (success, failure, time-out, no output, wrong size) and ready-made inpainted images.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/photo.hpp>

#include "core/inpaint/external_inpainter.h"
#include "core/inpaint/fsr_inpainter.h"
#include "core/inpaint/inpainter.h"
#include "core/inpaint/map_encoding.h"
#include "core/inpaint/map_set.h"
#include "core/inpaint/opencv_inpainter.h"
#include "core/inpaint/precomputed_inpainter.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

namespace fs = std::filesystem;

constexpr int W = 40, H = 32;

// A smooth image: channel c = 0.2 + 0.5 x/W + 0.2 y/H + 0.05 c (all in [0, 1]).
Image gradient_image(int channels) {
  Image img(W, H, channels);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < channels; ++c)
        img.pixels[(size_t(y) * W + x) * channels + c] = 0.2f + 0.5f * float(x) / W + 0.2f * float(y) / H + 0.05f * c;
  return img;
}

// A square hole [x0, x0 + s) x [y0, y0 + s).
Mask square_mask(int x0, int y0, int s) {
  Mask m(W, H);
  for (int y = y0; y < y0 + s; ++y)
    for (int x = x0; x < x0 + s; ++x) m.set(x, y, true);
  return m;
}

// Overwrites the hole with junk so that a fill that ignored the mask would show.
void scribble(Image& img, const Mask& m) {
  for (size_t p = 0; p < img.pixel_count(); ++p)
    if (m.data[p])
      for (int c = 0; c < img.channels; ++c) img.pixels[p * img.channels + c] = (p + c) % 2 ? 1.0f : 0.0f;
}

float max_error_in(const Image& a, const Image& b, const Mask& m) {
  float e = 0;
  for (size_t p = 0; p < a.pixel_count(); ++p)
    if (m.data[p])
      for (int c = 0; c < a.channels; ++c)
        e = std::max(e, std::fabs(a.pixels[p * a.channels + c] - b.pixels[p * a.channels + c]));
  return e;
}

// Pixels outside the mask are the very same bits.
void expect_outside_identical(const Image& in, const Image& out, const Mask& m) {
  ASSERT_EQ(in.channels, out.channels);
  size_t differing = 0;
  for (size_t p = 0; p < in.pixel_count(); ++p)
    if (!m.data[p] && std::memcmp(&in.pixels[p * in.channels], &out.pixels[p * in.channels],
                                  sizeof(float) * size_t(in.channels)) != 0)
      ++differing;
  EXPECT_EQ(differing, 0u);
}

std::vector<std::string> backends() {
  std::vector<std::string> b = {"telea", "ns", "harmonic"};
  if (fsr_available()) b.push_back("fsr");
  return b;
}

TEST(InpaintOpenCv, FloatSingleChannelAtAnyRangeIsSupported) {
  // What OpenCvInpainter relies on: cv::inpaint takes CV_32FC1 with values far outside [0, 1].
  cv::Mat img(32, 32, CV_32FC1), mask(32, 32, CV_8UC1, cv::Scalar(0)), out;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) img.at<float>(y, x) = -500.0f + 3.0f * x + 1.0f * y;
  const cv::Mat truth = img.clone();
  for (int y = 8; y < 16; ++y)
    for (int x = 8; x < 16; ++x) {
      mask.at<uint8_t>(y, x) = 255;
      img.at<float>(y, x) = 1e4f;
    }
  cv::inpaint(img, mask, out, 3, cv::INPAINT_TELEA);
  ASSERT_EQ(out.type(), CV_32FC1);
  for (int y = 8; y < 16; ++y)
    for (int x = 8; x < 16; ++x) EXPECT_NEAR(out.at<float>(y, x), truth.at<float>(y, x), 15.0f);  // 4 px/px slope
}

TEST(InpaintBackends, FillSmoothGradientAndKeepOutsideBits) {
  const Image truth = gradient_image(3);
  const Mask hole = square_mask(14, 10, 10);
  Image input = gradient_image(3);
  scribble(input, hole);
  for (const std::string& spec : backends()) {
    SCOPED_TRACE(spec);
    const auto inp = make_inpainter(spec);
    const Image out = inpaint_map(*inp, input, hole, {"v", "rgb", MapKind::Color});
    ASSERT_EQ(out.width, W);
    ASSERT_EQ(out.channels, 3);
    // The gradient changes by 0.0125 + 0.00625 per pixel across a 10-pixel hole: diffusion fills are
    // off by a few pixels' worth of slope; the harmonic fill is exact on an affine image.
    EXPECT_LT(max_error_in(out, truth, hole), spec == "harmonic" ? 1e-4f : 0.06f);
    expect_outside_identical(input, out, hole);
  }
}

TEST(InpaintBackends, NormalsComeBackUnitLength) {
  Image normals(W, H, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float v[3] = {0.3f * (float(x) / W - 0.5f), 0.3f * (float(y) / H - 0.5f), -1.0f};
      const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (int c = 0; c < 3; ++c) normals.pixels[(size_t(y) * W + x) * 3 + c] = v[c] / len * 2.0f;  // not unit
    }
  const Mask hole = square_mask(10, 8, 12);
  for (const std::string& spec : backends()) {
    SCOPED_TRACE(spec);
    const Image out = inpaint_map(*make_inpainter(spec), normals, hole, {"v", "normal", MapKind::Normal});
    for (size_t p = 0; p < out.pixel_count(); ++p) {
      if (!hole.data[p]) continue;
      const float* n = &out.pixels[p * 3];
      EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0f, 1e-5f);
      const float* t = &normals.pixels[p * 3];
      const float cosang = (n[0] * t[0] + n[1] * t[1] + n[2] * t[2]) / 2.0f;
      EXPECT_GT(cosang, std::cos(3.0f * 3.14159265f / 180.0f));  // within 3 degrees
    }
    expect_outside_identical(normals, out, hole);
  }
}

TEST(InpaintBackends, DepthOfAPlaneIsFilledInInverseDepthIgnoringEmptyPixels) {
  // A tilted plane: 1/z is affine in the pixel coordinates. Left of the hole a band has no surface
  // (z = 0); a fill that used those pixels as sources would pull the depth towards 0 or infinity.
  Image depth(W, H, 1);
  Image truth(W, H, 1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float z = 1.0f / (0.25f + 0.004f * x + 0.002f * y);
      truth.pixels[size_t(y) * W + x] = z;
      depth.pixels[size_t(y) * W + x] = (x >= 6 && x < 12 && y >= 8 && y < 24) ? 0.0f : z;
    }
  const Mask hole = square_mask(12, 8, 14);
  for (const std::string& spec : backends()) {
    SCOPED_TRACE(spec);
    const Image out = inpaint_map(*make_inpainter(spec), depth, hole, {"v", "depth", MapKind::Depth});
    for (size_t p = 0; p < out.pixel_count(); ++p)
      if (hole.data[p])
        EXPECT_NEAR(out.pixels[p], truth.pixels[p], (spec == "harmonic" ? 1e-4f : 0.06f) * truth.pixels[p]) << "pixel " << p;
    expect_outside_identical(depth, out, hole);  // including the z = 0 band
  }
}

TEST(InpaintBackends, UnitMapsStayInRangeAndDataMapsKeepTheirScale) {
  Image rough(W, H, 1), data(W, H, 2);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t p = size_t(y) * W + x;
      rough.pixels[p] = x < W / 2 ? 0.0f : 1.0f;  // a step: overshoot would leave [0, 1]
      data.pixels[p * 2 + 0] = -1000.0f + 50.0f * x;
      data.pixels[p * 2 + 1] = 3e-3f * y;
    }
  const Mask hole = square_mask(14, 10, 12);
  for (const std::string& spec : backends()) {
    SCOPED_TRACE(spec);
    const auto inp = make_inpainter(spec);
    const Image r = inpaint_map(*inp, rough, hole, {"v", "roughness", MapKind::Unit});
    for (size_t p = 0; p < r.pixel_count(); ++p) {
      EXPECT_GE(r.pixels[p], 0.0f);
      EXPECT_LE(r.pixels[p], 1.0f);
    }
    const Image d = inpaint_map(*inp, data, hole, {"v", "data", MapKind::Data});
    for (size_t p = 0; p < d.pixel_count(); ++p) {
      if (!hole.data[p]) continue;
      // The hole spans ~35% of each channel's range; diffusion fills stay within 15% of it (Telea lags
      // by a few pixels' worth of slope), the harmonic fill is exact on these ramps: the scale is kept.
      const float tol = spec == "harmonic" ? 1e-3f : 0.15f;
      EXPECT_NEAR(d.pixels[p * 2 + 0], data.pixels[p * 2 + 0], tol * 1950.0f);
      EXPECT_NEAR(d.pixels[p * 2 + 1], data.pixels[p * 2 + 1], tol * 3e-3f * H);
    }
    expect_outside_identical(data, d, hole);
  }
}

TEST(InpaintMap, BadInputIsAnErrorNamingTheMap) {
  const auto inp = make_inpainter("telea");
  const Image img = gradient_image(3);
  EXPECT_THROW(inpaint_map(*inp, img, Mask(W + 1, H), {"r_007", "rgb", MapKind::Color}), Error);
  try {
    inpaint_map(*inp, img, Mask(W + 1, H), {"r_007", "rgb", MapKind::Color});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("r_007/rgb"), std::string::npos) << e.what();
  }
  Image nan_img = gradient_image(3);
  nan_img.pixels[5] = std::nanf("");
  EXPECT_THROW(inpaint_map(*inp, nan_img, square_mask(20, 20, 4), {"v", "rgb", MapKind::Color}), Error);
  EXPECT_THROW(inpaint_map(*inp, gradient_image(1), square_mask(20, 20, 4), {"v", "normal", MapKind::Normal}), Error);
  Image no_depth(W, H, 1);
  no_depth.pixels.fill_zero();
  EXPECT_THROW(inpaint_map(*inp, no_depth, square_mask(20, 20, 4), {"v", "depth", MapKind::Depth}), Error);
  // An empty mask is a plain copy.
  const Image same = inpaint_map(*inp, img, Mask(W, H), {"v", "rgb", MapKind::Color});
  expect_outside_identical(img, same, Mask(W, H));
}

TEST(InpaintFactory, NamesAndErrors) {
  EXPECT_NE(make_inpainter("telea")->name().find("telea"), std::string::npos);
  EXPECT_NE(make_inpainter("ns:5")->name().find("radius 5"), std::string::npos);
  EXPECT_NE(make_inpainter("cmd:cp {image} {out}")->name().find("cp {image} {out}"), std::string::npos);
  EXPECT_THROW(make_inpainter("telea:-1"), Error);
  EXPECT_THROW(make_inpainter("cmd:"), Error);
  EXPECT_THROW(make_inpainter("cmd:lama {image}"), Error);  // no {out}
  EXPECT_THROW(make_inpainter("dir:/nonexistent/folder"), Error);
  try {
    make_inpainter("lama");
    FAIL() << "no error for an unknown inpainter";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("telea"), std::string::npos) << e.what();
  }
  if (fsr_available()) EXPECT_NE(make_inpainter("fsr-best")->name().find("best"), std::string::npos);
  else EXPECT_THROW(make_inpainter("fsr"), Error);
}

// --- external programs ---------------------------------------------------------------------------

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(InpaintExternal, PlaceholdersAreQuotedWords) {
  EXPECT_EQ(ExternalInpainter::expand("tool {image} -m {mask} -o {out} {view}/{map}", "/a b/i.png", "m.png",
                                      "it's.png", "r_1", "rgb"),
            "tool '/a b/i.png' -m 'm.png' -o 'it'\\''s.png' 'r_1'/'rgb'");
  // A value that contains a placeholder is not expanded again.
  EXPECT_EQ(ExternalInpainter::expand("{image} {out}", "{out}", "", "o", "", ""), "'{out}' 'o'");
}

TEST(InpaintExternal, CopyCommandReturnsTheEncodedInput) {
  const fs::path tmp = test::scratch_dir("inpaint_external_cp") / "dir with space and 'quote'";
  fs::create_directories(tmp);
  ExternalInpainterOptions opt;
  opt.temp_root = tmp;
  const ExternalInpainter inp("cp {image} {out}", opt);
  const Image img = gradient_image(3);
  const Mask hole = square_mask(5, 5, 8);
  const Image out = inpaint_map(inp, img, hole, {"r 1", "rgb", MapKind::Color});
  EXPECT_LE(max_error_in(out, img, hole), 0.5f / 255.0f + 1e-6f);  // 8-bit round trip inside the hole
  expect_outside_identical(img, out, hole);
  EXPECT_TRUE(fs::is_empty(tmp)) << "temporary folder left behind";

  // Depth goes through 16 bits: the round trip is much finer than 8 bits.
  Image depth(W, H, 1);
  for (size_t p = 0; p < depth.pixel_count(); ++p) depth.pixels[p] = 2.0f + 0.01f * float(p % W);
  const Image d = inpaint_map(inp, depth, hole, {"r 1", "depth", MapKind::Depth});
  for (size_t p = 0; p < d.pixel_count(); ++p)
    if (hole.data[p]) EXPECT_NEAR(d.pixels[p], depth.pixels[p], 2e-4f);
}

TEST(InpaintExternal, FailureTimeoutAndMissingOutputAreClearErrors) {
  const Image img = gradient_image(3);
  const Mask hole = square_mask(5, 5, 8);
  const MapInfo info{"r_3", "rgb", MapKind::Color};

  std::string msg = error_of([&] { inpaint_map(ExternalInpainter("false {image} {out}"), img, hole, info); });
  EXPECT_NE(msg.find("`false '"), std::string::npos) << msg;
  EXPECT_NE(msg.find("exited with status 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("r_3/rgb"), std::string::npos) << msg;

  msg = error_of([&] { inpaint_map(ExternalInpainter("echo 'model weights missing' >&2; exit 3 # {image} {out}"), img, hole, info); });
  EXPECT_NE(msg.find("exited with status 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("model weights missing"), std::string::npos) << msg;  // stderr tail

  ExternalInpainterOptions quick;
  quick.timeout_s = 1.0;
  const auto t0 = std::chrono::steady_clock::now();
  msg = error_of([&] { inpaint_map(ExternalInpainter("sleep 5 # {image} {out}", quick), img, hole, info); });
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(msg.find("timed out after 1 s"), std::string::npos) << msg;
  EXPECT_NE(msg.find("sleep 5"), std::string::npos) << msg;
  EXPECT_LT(secs, 3.0);

  msg = error_of([&] { inpaint_map(ExternalInpainter("true {image} {out}"), img, hole, info); });
  EXPECT_NE(msg.find("wrote no image"), std::string::npos) << msg;

  const fs::path small = test::scratch_dir("inpaint_external_small") / "small.png";
  save_png(small, Image(16, 16, 3));
  msg = error_of([&] { inpaint_map(ExternalInpainter("cp " + small.string() + " {out} # {image}"), img, hole, info); });
  EXPECT_NE(msg.find("16x16"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 40x32"), std::string::npos) << msg;

  msg = error_of([&] { inpaint_map(ExternalInpainter("echo not a png > {out} # {image}"), img, hole, info); });
  EXPECT_NE(msg.find("unreadable"), std::string::npos) << msg;

  ExternalInpainterOptions stop;
  stop.should_stop = [] { return true; };
  msg = error_of([&] { inpaint_map(ExternalInpainter("sleep 5 # {image} {out}", stop), img, hole, info); });
  EXPECT_NE(msg.find("stopped"), std::string::npos) << msg;
}

TEST(InpaintExternal, OneChannelMapsReadBackFromColourResults) {
  // A program that always writes RGB (as most do): a one-channel map takes the mean of R, G, B.
  const fs::path tmp = test::scratch_dir("inpaint_external_grey");
  const fs::path rgb_file = tmp / "rgb.png";
  Image rgb(W, H, 3);
  for (size_t p = 0; p < rgb.pixel_count(); ++p) {
    rgb.pixels[p * 3 + 0] = 0.2f;
    rgb.pixels[p * 3 + 1] = 0.4f;
    rgb.pixels[p * 3 + 2] = 0.6f;
  }
  save_png(rgb_file, rgb);
  Image rough(W, H, 1);
  for (size_t p = 0; p < rough.pixel_count(); ++p) rough.pixels[p] = 0.9f;
  const Mask hole = square_mask(5, 5, 8);
  const Image out = inpaint_map(ExternalInpainter("cp " + rgb_file.string() + " {out} # {image}"), rough, hole,
                                {"v", "roughness", MapKind::Unit});
  for (size_t p = 0; p < out.pixel_count(); ++p) EXPECT_NEAR(out.pixels[p], hole.data[p] ? 0.4f : 0.9f, 1e-2f);
}

// --- ready-made inpainted images -----------------------------------------------------------------

TEST(InpaintPrecomputed, ReadsViewMapFilesWithTheSameEncoding) {
  const fs::path inputs = test::scratch_dir("inpaint_precomputed_in"), outputs = test::scratch_dir("inpaint_precomputed_out");
  MapSet maps;
  maps.rgb = gradient_image(3);
  maps.depth = Image(W, H, 1);
  for (size_t p = 0; p < maps.depth.pixel_count(); ++p) maps.depth.pixels[p] = 1.5f + 0.02f * float(p / W);
  maps.roughness = gradient_image(1);
  const Mask hole = square_mask(8, 6, 10);
  write_inpainting_inputs(inputs, maps, hole, "r_004");
  for (const char* f : {"r_004_rgb.png", "r_004_rgb_mask.png", "r_004_depth.png", "r_004_depth_mask.png",
                        "r_004_roughness.png", "r_004_roughness_mask.png"})
    EXPECT_TRUE(fs::exists(inputs / f)) << f;
  EXPECT_FALSE(fs::exists(inputs / "r_004_normal.png"));  // absent maps are skipped
  // "Inpaint" offline with a copy: the results must decode to the input (16-bit depth, 8-bit colour).
  for (const char* m : {"rgb", "depth", "roughness"})
    fs::copy_file(inputs / (std::string("r_004_") + m + ".png"), outputs / (std::string("r_004_") + m + ".png"));
  const PrecomputedInpainter pre(outputs);
  const MapSet filled = inpaint_map_set(pre, maps, hole, "r_004");
  EXPECT_LE(max_error_in(filled.rgb, maps.rgb, hole), 0.5f / 255.0f + 1e-6f);
  EXPECT_LE(max_error_in(filled.depth, maps.depth, hole), 1e-3f);
  EXPECT_EQ(filled.normal.pixel_count(), 0u);
  expect_outside_identical(maps.depth, filled.depth, hole);

  // A missing map names the file; with a fallback it is filled by the fallback.
  MapSet with_normal;
  with_normal.normal = Image(W, H, 3);
  for (size_t p = 0; p < with_normal.normal.pixel_count(); ++p) {
    with_normal.normal.pixels[p * 3 + 0] = 0.0f;
    with_normal.normal.pixels[p * 3 + 1] = 0.0f;
    with_normal.normal.pixels[p * 3 + 2] = -1.0f;
  }
  const std::string msg = error_of([&] { inpaint_map_set(pre, with_normal, hole, "r_004"); });
  EXPECT_NE(msg.find("r_004_normal.png"), std::string::npos) << msg;
  const PrecomputedInpainter with_fallback(outputs, std::shared_ptr<const Inpainter>(make_inpainter("telea")));
  const MapSet n = inpaint_map_set(with_fallback, with_normal, hole, "r_004");
  EXPECT_NEAR(n.normal.pixels[(size_t(10) * W + 12) * 3 + 2], -1.0f, 1e-5f);

  // Wrong size.
  save_png(outputs / "r_009_rgb.png", Image(8, 8, 3));
  EXPECT_NE(error_of([&] { inpaint_map(pre, maps.rgb, hole, {"r_009", "rgb", MapKind::Color}); }).find("8x8"),
            std::string::npos);
}

// --- masks ---------------------------------------------------------------------------------------

TEST(InpaintMask, OpenRemovesSpecksAndCloseFillsPinholes) {
  Mask m(16, 16);
  m.set(2, 2, true);  // a speck
  for (int y = 6; y < 12; ++y)
    for (int x = 6; x < 12; ++x) m.set(x, y, true);
  const Mask opened = open_mask(m, 1);
  EXPECT_FALSE(opened(2, 2));
  EXPECT_EQ(count_set(opened), 36u);
  m.set(8, 8, false);  // a pinhole
  const Mask closed = close_mask(m, 1);
  EXPECT_TRUE(closed(8, 8));
  EXPECT_TRUE(closed(2, 2));
  EXPECT_EQ(count_set(closed), 37u);
  // The border counts as set for erosion: a mask filling the image survives an opening.
  EXPECT_EQ(count_set(open_mask(Mask(5, 5, 255), 1)), 25u);
  const fs::path f = test::scratch_dir("inpaint_mask_png") / "m.png";
  save_mask_png(f, m);
  EXPECT_EQ(read_mask_png(f).data, m.data);
}

}  // namespace
}  // namespace goris
