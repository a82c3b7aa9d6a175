// The capture import's pieces that need no COLMAP (frame picking, progress lines, the pose alignment, bad
// input refused before any work), and a short video clip of the embedded scene imported end to end where
// COLMAP is installed (skipped with a message elsewhere).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/capture/capture.h"
#include "core/capture/capture_frames.h"
#include "core/capture/colmap_progress.h"
#include "core/capture/pose_alignment.h"
#include "core/io/dataset.h"
#include "core/util/logged_process.h"
#include "tests/support/capture_inputs.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;
using namespace goris;
using namespace goris::capture;

TEST(Capture, PicksTheSharpestFrameOfEachWindow) {
  const std::vector<double> scores{1, 5, 2, 9, 3, 3, 0, 7, 1, 1};
  EXPECT_EQ(pick_sharpest(scores, 2), (std::vector<int>{3, 7}));
  EXPECT_EQ(pick_sharpest(scores, 5), (std::vector<int>{1, 3, 4, 7, 8}));
  EXPECT_EQ(pick_sharpest(scores, 0).size(), scores.size());
  EXPECT_EQ(pick_sharpest(scores, 20).size(), scores.size());
}

TEST(Capture, SharpnessFallsWithBlur) {
  cv::Mat img(96, 96, CV_8UC3);
  cv::randu(img, cv::Scalar::all(0), cv::Scalar::all(255));
  cv::Mat blurred;
  cv::GaussianBlur(img, blurred, cv::Size(9, 9), 3.0);
  EXPECT_GT(sharpness(img), 10 * sharpness(blurred));
}

TEST(Capture, ReadsColmapProgressLines) {
  auto c = parse_colmap_progress("Processed file [3/50]", 50);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->done, 3);
  EXPECT_EQ(c->total, 50);
  c = parse_colmap_progress("Matching block [2/5, 3/5] in 1.234s", 50);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->done, 8);
  EXPECT_EQ(c->total, 25);
  c = parse_colmap_progress("Registering image #12 (7)", 40);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->done, 7);
  EXPECT_EQ(c->total, 40);
  c = parse_colmap_progress("  Undistorting image [4/9]", 9);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->done, 4);
  EXPECT_FALSE(parse_colmap_progress("Bundle adjustment report", 9));
}

TEST(Capture, SimilarityFitRecoversScaleRotationTranslation) {
  std::vector<glm::dvec3> from{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}, {1, 1, 1}};
  const double a = 0.7;
  const glm::dmat3 R{{std::cos(a), std::sin(a), 0}, {-std::sin(a), std::cos(a), 0}, {0, 0, 1}};
  Similarity truth;
  truth.scale = 2.5, truth.rotation = R, truth.translation = {1, -2, 3};
  std::vector<glm::dvec3> to;
  for (const auto& p : from) to.push_back(truth.apply(p));
  const Similarity fit = fit_similarity(from, to);
  EXPECT_NEAR(fit.scale, 2.5, 1e-9);
  for (size_t i = 0; i < from.size(); ++i) EXPECT_LT(glm::length(fit.apply(from[i]) - to[i]), 1e-9);
}

TEST(Capture, PosesOfADataSetAgreeWithThemselves) {
  DatasetOptions all;
  all.test_every = 0;
  Dataset d = load_dataset(test::resource_dir() / "default_scene", all);
  d.test.clear();  // its test views reuse the train views' names (r_000...)
  const PoseComparison c = compare_poses(d, d, "default_scene");
  EXPECT_EQ(c.matched, int(d.view_count()));
  EXPECT_LT(c.max_error, 1e-5);
  EXPECT_LT(c.mean_angle_deg, 0.05);
}

TEST(Capture, RefusesBadInputBeforeAnyWork) {
  const fs::path dir = test::scratch_dir("capture_bad_input");
  CaptureOptions o;
  o.out = dir / "out";
  o.input = dir / "missing";
  test::expect_error([&] { run_capture(o); }, "missing: not found");
  o.input = test::photo_folder(dir / "two", 2);
  test::expect_error([&] { run_capture(o); }, "only 2 photos: a capture needs at least 3");
  o.input = dir / "broken.mp4";
  std::ofstream(o.input) << "not a video";
  test::expect_error([&] { run_capture(o); }, "broken.mp4: cannot read the video");
  o.input = dir / "notes.txt";
  std::ofstream(o.input) << "x";
  test::expect_error([&] { run_capture(o); }, "not a folder of images or a video file");
  // COLMAP missing: an explicit program that is not there names the apt command.
  o.input = test::photo_folder(dir / "five", 5);
  o.colmap = dir / "no_colmap";
  test::expect_error([&] { run_capture(o); }, "sudo apt-get install colmap");
  // The output guard: an existing folder, a folder inside the input, a folder inside a data set.
  o.colmap.clear();
  fs::create_directories(dir / "exists");
  o.out = dir / "exists";
  test::expect_error([&] { run_capture(o); }, "exists already");
  o.out = o.input / "captured";
  test::expect_error([&] { run_capture(o); }, "lies inside the input folder");
  EXPECT_FALSE(fs::exists(o.out));
  o.out = test::resource_dir() / "default_scene" / "captured";
  o.colmap = "/bin/true";  // gets past the COLMAP check wherever COLMAP is absent
  test::expect_error([&] { run_capture(o); }, "data set");
  EXPECT_FALSE(fs::exists(o.out));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".capture-tmp"), std::string::npos) << e.path();
}

TEST(Capture, ColmapMissingOnPath) {
  const fs::path dir = test::scratch_dir("capture_no_colmap");
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  setenv("PATH", (dir / "empty_bin").c_str(), 1);
  std::string message;
  try {
    find_colmap();
  } catch (const Error& e) {
    message = e.what();
  }
  setenv("PATH", saved.c_str(), 1);
  EXPECT_NE(message.find("COLMAP not found on PATH"), std::string::npos) << message;
  EXPECT_NE(message.find("sudo apt-get install colmap"), std::string::npos) << message;
}

// A clip of a rendered scene's views in orbit order (by azimuth), written by OpenCV, imported with COLMAP;
// the result loads as a data set and `goris train` runs a few iterations on it. The scene is the shared
// NeRF-synthetic lego (400 px, textured all over): the embedded 128 px scene gives COLMAP too few features to
// start a model (measured: no initial pair among 40 frames upscaled to 256 px).
TEST(Capture, VideoOfARenderedOrbitImportsAndTrains) {
  if (!find_on_path("colmap")) GTEST_SKIP() << "needs COLMAP (sudo apt-get install colmap, or ./dev setup)";
  GORIS_REQUIRE_SHARED("datasets/lego");
  const fs::path dir = test::scratch_dir("capture_video");
  const Dataset scene = load_dataset(test::shared_dir() / "datasets" / "lego");
  const fs::path clip = dir / "orbit.mp4";
  const int frames = test::write_orbit_clip(scene, clip);
  ASSERT_GT(frames, 0);

  CaptureOptions o;
  o.input = clip;
  o.out = dir / "captured";
  o.max_images = 20;
  const CaptureReport r = run_capture(o);
  EXPECT_TRUE(r.from_video);
  EXPECT_EQ(r.candidates, frames);
  EXPECT_EQ(r.images, std::min(20, frames));
  EXPECT_GE(r.registered, r.images / 2);  // measured: 14 of 20 (frames far apart in height stay out)
  EXPECT_TRUE(fs::exists(o.out / "capture_report.json"));
  const Dataset d = load_dataset(o.out);
  EXPECT_EQ(int(d.view_count()), r.registered);
  EXPECT_GT(d.points.size(), 50u);

  const fs::path goris = fs::path(GORIS_BINARY_DIR) / "bin" / "goris";
  if (!fs::exists(goris)) GTEST_SKIP() << "imported; the training step needs " << goris;
  const std::string cmd = "'" + goris.string() + "' train '" + o.out.string() + "' --out '" + (dir / "run").string() +
                          "' --iters 20 --resolution 64 --device cpu --checkpoint-every 0 > '" + (dir / "train.log").string() + "' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "see " << (dir / "train.log");
  EXPECT_TRUE(fs::exists(dir / "run" / "point_cloud.ply"));
}
