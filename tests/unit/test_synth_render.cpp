// A tiny real render with Blender (32x32, a few views, few samples): files, JSON counts, masks, and that
// removing the target changes the test views only around the target and on glossy surfaces (where its
// reflection was). Skips with a message when Blender is not installed.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/dataset.h"
#include "core/synth/blender_process.h"
#include "core/synth/synth.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;
using namespace goris::synth;

namespace {
cv::Mat read(const fs::path& p, int flags) {
  cv::Mat m = cv::imread(p.string(), flags);
  if (m.empty()) ADD_FAILURE() << "cannot read " << p;
  return m;
}
}  // namespace

TEST(SynthRender, TinyGlossyTable) {
  try {
    find_blender();
  } catch (const goris::Error& e) {
    GTEST_SKIP() << "Blender is not installed: " << e.what();
  }
  fs::path out = goris::test::scratch_dir("synth_render") / "scene";
  SynthJob job;
  job.options.preset = "glossy-table";
  job.options.resolution = 32;
  job.options.samples = 8;
  job.options.train_views = 2;
  job.options.test_views = 3;
  job.options.seed = 3;
  job.script = goris::test::resource_dir() / "synth" / "render_scene.py";
  job.out = out;
  int frames = 0;
  job.on_frame = [&](int done, int total) {
    ++frames;
    EXPECT_EQ(done, frames);
    EXPECT_EQ(total, 5);
  };
  run_synth(job);
  EXPECT_EQ(frames, 5);
  EXPECT_FALSE(fs::exists(out.string() + ".synth-tmp"));

  for (const char* f : {"scene.json", "blender.log", "transforms_train.json", "transforms_test.json", "train/gt/diffcol_000.exr",
                        "train/gt/glosscol_001.exr", "train/gt/normal_000.exr", "train/gt/depth_001.exr"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  nlohmann::json train = nlohmann::json::parse(std::ifstream(out / "transforms_train.json"));
  EXPECT_EQ(train["frames"].size(), 2u);
  EXPECT_EQ(train["frames"][1]["file_path"], "./train/r_001");

  goris::Dataset d = goris::load_dataset(out);
  ASSERT_EQ(d.train.size(), 2u);
  ASSERT_EQ(d.test.size(), 3u);
  for (const auto& v : d.train) {
    ASSERT_TRUE(v.object_mask && v.glossy_mask) << v.name;
    cv::Mat rgba = read(v.image, cv::IMREAD_UNCHANGED);
    EXPECT_EQ(rgba.channels(), 4);
    EXPECT_EQ(rgba.cols, 32);
    EXPECT_GT(cv::countNonZero(read(*v.object_mask, cv::IMREAD_GRAYSCALE) > 128), 4) << v.name;
    EXPECT_GT(cv::countNonZero(read(*v.glossy_mask, cv::IMREAD_GRAYSCALE) > 128), 50) << v.name;
  }
  for (const auto& v : d.test) {
    ASSERT_TRUE(v.object_mask && v.full_image) << v.name;
    cv::Mat mask = read(*v.object_mask, cv::IMREAD_GRAYSCALE);
    cv::Mat gloss = read(out / "test" / "gt" / ("gloss_" + v.name.substr(2) + ".png"), cv::IMREAD_GRAYSCALE);
    cv::Mat full = read(*v.full_image, cv::IMREAD_UNCHANGED), removed = read(v.image, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(full.size(), removed.size());
    EXPECT_GT(cv::countNonZero(mask > 128), 4) << v.name;

    cv::Mat diff;
    cv::absdiff(full, removed, diff);
    diff = diff.reshape(1, diff.rows * diff.cols);
    cv::reduce(diff, diff, 1, cv::REDUCE_MAX);
    diff = diff.reshape(1, full.rows);  // per pixel: largest channel difference (alpha included)
    // Where the target was, removing it must change the image.
    double inside = cv::mean(diff, mask > 200)[0];
    EXPECT_GT(inside, 20.0) << v.name;
    // Elsewhere only its reflection (glossy surfaces), shadow and bounced light may change: away from the
    // target, on non-glossy pixels, the two renders agree (Cycles samples each pixel the same way, so only
    // paths that met the target differ).
    cv::Mat near_target, near_gloss;
    cv::dilate(mask > 0, near_target, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
    cv::dilate(gloss > 0, near_gloss, cv::getStructuringElement(cv::MORPH_ELLIPSE, {3, 3}));
    cv::Mat elsewhere = ~(near_target | near_gloss);
    ASSERT_GT(cv::countNonZero(elsewhere), 20) << v.name;
    EXPECT_LT(cv::mean(diff, elsewhere)[0], 3.0) << v.name;
    cv::Mat changed = (diff > 40) & elsewhere;
    EXPECT_LE(cv::countNonZero(changed), cv::countNonZero(elsewhere) / 50) << v.name;
  }
}

TEST(SynthRender, MissingBlenderNamesTheInstallCommand) {
  try {
    find_blender("/nonexistent/blender");
    FAIL() << "expected an error";
  } catch (const goris::Error& e) {
    EXPECT_NE(std::string(e.what()).find("sudo apt-get install blender"), std::string::npos) << e.what();
  }
}

TEST(SynthRender, FailedRenderReportsTheLog) {
  // /bin/false stands in for a Blender that fails at once: the error names OUT/blender.log, and no
  // half data set is left under the final name.
  fs::path out = goris::test::scratch_dir("synth_render_fail") / "scene";
  SynthJob job;
  job.options.train_views = 1;
  job.options.test_views = 1;
  job.script = goris::test::resource_dir() / "synth" / "render_scene.py";
  job.blender = "/bin/false";
  job.out = out;
  try {
    run_synth(job);
    FAIL() << "expected an error";
  } catch (const goris::Error& e) {
    EXPECT_NE(std::string(e.what()).find((out / "blender.log").string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(out / "blender.log"));
  EXPECT_FALSE(fs::exists(out / "scene.json"));
  EXPECT_FALSE(fs::exists(out.string() + ".synth-tmp"));
}
