// A tiny real render with Blender (32x32, a few views, few samples): files, JSON counts, masks, and that
// removing the target changes the test views only around the target and on glossy surfaces (where its
// reflection was). Skips with a message when Blender is not installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/dataset.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "tools/synth/blender_process.h"
#include "tools/synth/synth.h"

namespace fs = std::filesystem;
using namespace goris::synth;

namespace {
cv::Mat read(const fs::path& p, int flags) {
  cv::Mat m = cv::imread(p.string(), flags);
  if (m.empty()) ADD_FAILURE() << "cannot read " << p;
  return m;
}
// On pixels fully inside the glossy table top, the ground-truth maps hold the table's material from
// scene.json: F0 (metal: its colour; marble: 0.08 * specular), roughness, an up-facing normal and a
// depth within the camera's range.
void check_table_ground_truth(const fs::path& out) {
  ::setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 1);  // OpenCV reads EXR only when asked to
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(out / "scene.json"));
  nlohmann::json table;
  for (const auto& o : scene["objects"])
    if (o["name"] == "table") table = o["material"];
  ASSERT_FALSE(table.is_null());
  const double metallic = table["metallic"], spec = table["specular"], rough = table["roughness"];
  cv::Mat gloss = read(out / "train/gloss_000.png", cv::IMREAD_GRAYSCALE);
  cv::Mat f0 = read(out / "train/gt/f0_000.exr", cv::IMREAD_UNCHANGED);
  cv::Mat roughness = read(out / "train/gt/roughness_000.exr", cv::IMREAD_UNCHANGED);
  cv::Mat normal = read(out / "train/gt/normal_000.exr", cv::IMREAD_UNCHANGED);
  cv::Mat depth = read(out / "train/gt/depth_000.exr", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(f0.type(), CV_32FC3);
  ASSERT_EQ(f0.size(), gloss.size());
  cv::Mat inside;
  cv::erode(gloss == 255, inside, cv::Mat());  // away from the table's edges and the objects on it
  ASSERT_GT(cv::countNonZero(inside), 20);
  cv::Scalar f0_mean = cv::mean(f0, inside), n_mean = cv::mean(normal, inside);
  if (metallic > 0.5) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f0_mean[2 - c], double(table["color"][c]), 0.02) << "F0 channel " << c;
  } else {  // marble: textured base colour does not enter a dielectric's F0
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f0_mean[c], 0.08 * spec, 0.01) << "F0 channel " << c;
  }
  EXPECT_NEAR(cv::mean(roughness, inside)[0], rough, 0.01);
  EXPECT_NEAR(n_mean[0], 1.0, 0.02);  // BGR: the table's normal is +Z (Blender's up)
  double lo = 0, hi = 0;
  std::vector<cv::Mat> dch;
  cv::split(depth, dch);
  cv::minMaxLoc(dch[0], &lo, &hi, nullptr, nullptr, inside);
  EXPECT_GT(lo, 2.0);  // cameras are 5.2 m from the table's centre, the table's radius is 1.5 m
  EXPECT_LT(hi, 8.0);
}
// A 32-pixel glossy-table scene without ground-truth maps, rendered into a new scratch folder.
SynthJob tiny_scene(const std::string& name, int train_views, int test_views) {
  SynthJob job;
  job.options.resolution = 32;
  job.options.samples = 8;
  job.options.train_views = train_views;
  job.options.test_views = test_views;
  job.options.seed = 3;
  job.options.ground_truth_maps = false;
  job.script = goris::test::resource_dir() / "synth" / "render_scene.py";
  job.out = goris::test::scratch_dir(name) / "scene";
  run_synth(job);
  return job;
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
  job.contact_sheet = true;
  int frames = 0;
  job.on_frame = [&](int done, int total) {
    ++frames;
    EXPECT_EQ(done, frames);
    EXPECT_EQ(total, 5);
  };
  run_synth(job);
  EXPECT_EQ(frames, 5);
  EXPECT_FALSE(fs::exists(out.string() + ".synth-tmp"));

  for (const char* f : {"scene.json", "blender.log", "transforms_train.json", "transforms_test.json", "contact_sheet.png",
                        "train/gt/diffcol_000.exr", "train/gt/glosscol_001.exr", "train/gt/normal_000.exr",
                        "train/gt/depth_001.exr", "train/gt/encoding.json"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  nlohmann::json encoding = nlohmann::json::parse(std::ifstream(out / "train/gt/encoding.json"));
  for (const char* map : {"diffcol", "glosscol", "normal", "depth", "f0", "roughness"}) {
    EXPECT_TRUE(encoding["maps"].contains(map)) << map;
    EXPECT_TRUE(fs::is_regular_file(out / "train" / "gt" / (std::string(map) + "_001.exr"))) << map;
  }
  check_table_ground_truth(out);
  cv::Mat sheet = read(out / "contact_sheet.png", cv::IMREAD_COLOR);
  EXPECT_GE(sheet.cols, 3 * 256);  // at least one enlarged triplet full_ | r_ | mask
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
    cv::Mat gloss = read(*v.glossy_mask, cv::IMREAD_GRAYSCALE);
    EXPECT_GT(cv::countNonZero(gloss > 128), 50) << v.name;
    // Masks are coverage: where the table's silhouette meets the transparent background, the glossy mask
    // follows the image's alpha (it cannot cover more of a pixel than all surfaces together do).
    std::vector<cv::Mat> ch;
    cv::split(rgba, ch);
    cv::Mat excess;
    cv::subtract(gloss, ch[3], excess);  // saturates at 0
    cv::Mat silhouette = (ch[3] > 0) & (ch[3] < 255) & (gloss > 0);
    ASSERT_GT(cv::countNonZero(silhouette), 0) << v.name;
    EXPECT_LT(cv::mean(excess, silhouette)[0], 40.0) << v.name;
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

TEST(SynthRender, TrainingViewsWithoutTheTarget) {
  try {
    find_blender();
  } catch (const goris::Error& e) {
    GTEST_SKIP() << "Blender is not installed: " << e.what();
  }
  const SynthJob job = tiny_scene("synth_train_after", 2, 1);
  const fs::path out = job.out;
  goris::synth::TrainAfterJob after{out, job.script, {}, {}};
  int frames = 0;
  after.on_frame = [&](int done, int total) {
    ++frames;
    EXPECT_EQ(total, 2);
    EXPECT_EQ(done, frames);
  };
  goris::synth::render_train_after(after);
  EXPECT_EQ(frames, 2);
  EXPECT_FALSE(fs::exists(out / "train_after.synth-tmp"));
  for (const char* v : {"000", "001"}) {
    // The same view without the target: where the target was the image changes, away from it and from the
    // glossy surface it is the training photo (Cycles samples each pixel the same way).
    cv::Mat with = read(out / "train" / (std::string("r_") + v + ".png"), cv::IMREAD_UNCHANGED);
    cv::Mat without = read(out / "train_after" / (std::string("r_") + v + ".png"), cv::IMREAD_UNCHANGED);
    cv::Mat mask = read(out / "train" / (std::string("mask_") + v + ".png"), cv::IMREAD_GRAYSCALE);
    cv::Mat gloss = read(out / "train" / (std::string("gloss_") + v + ".png"), cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(with.size(), without.size()) << v;
    ASSERT_EQ(with.channels(), without.channels()) << v;
    cv::Mat diff;
    cv::absdiff(with, without, diff);
    diff = diff.reshape(1, diff.rows * diff.cols);
    cv::reduce(diff, diff, 1, cv::REDUCE_MAX);
    diff = diff.reshape(1, with.rows);
    ASSERT_GT(cv::countNonZero(mask > 200), 0) << v;
    EXPECT_GT(cv::mean(diff, mask > 200)[0], 20.0) << v;
    cv::Mat near_target, near_gloss;
    cv::dilate(mask > 0, near_target, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
    cv::dilate(gloss > 0, near_gloss, cv::getStructuringElement(cv::MORPH_ELLIPSE, {3, 3}));
    cv::Mat elsewhere = ~(near_target | near_gloss);
    ASSERT_GT(cv::countNonZero(elsewhere), 20) << v;
    EXPECT_LT(cv::mean(diff, elsewhere)[0], 3.0) << v;
  }
  // Not a synth output: refused by name before Blender starts.
  fs::path empty = goris::test::scratch_dir("synth_train_after_empty");
  EXPECT_THROW(goris::synth::render_train_after({empty, job.script, {}, {}}), goris::Error);
}

// `test-only` (tools/reference_noise.py): the test views alone, here at more samples and another seed, into a
// new folder; the masks differ only at their anti-aliased edges, the beauty renders show the same scene.
TEST(SynthRender, TestViewsAlone) {
  fs::path blender;
  try {
    blender = find_blender();
  } catch (const goris::Error& e) {
    GTEST_SKIP() << "Blender is not installed: " << e.what();
  }
  const SynthJob job = tiny_scene("synth_test_only", 1, 2);
  const fs::path out = job.out;
  nlohmann::json desc = nlohmann::json::parse(std::ifstream(out / "scene.json"));
  desc["render"]["spp"] = 32;
  desc["render"]["seed"] = int(desc["render"]["seed"]) + 1;
  const fs::path again = goris::test::scratch_dir("synth_test_only_again");
  std::ofstream(again / "scene.json") << desc.dump();
  int frames = 0;
  const goris::ProcessResult r = run_logged(
      blender, {"-b", "--factory-startup", "--python", job.script.string(), "--", (again / "scene.json").string(),
                again.string(), "test-only"},
      again / "blender.log", [&](const std::string& line) { frames += line.rfind("GORIS_FRAME", 0) == 0; });
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(frames, 2);
  EXPECT_FALSE(fs::exists(again / "train" / "r_000.png"));  // no training view rendered
  EXPECT_FALSE(fs::exists(again / "transforms_train.json"));
  for (const char* v : {"000", "001"}) {
    for (const char* f : {"full_", "r_", "mask_"})
      ASSERT_TRUE(fs::is_regular_file(again / "test" / (std::string(f) + v + ".png"))) << f << v;
    cv::Mat m0 = read(out / "test" / (std::string("mask_") + v + ".png"), cv::IMREAD_GRAYSCALE);
    cv::Mat m1 = read(again / "test" / (std::string("mask_") + v + ".png"), cv::IMREAD_GRAYSCALE);
    cv::Mat mask_diff;
    cv::absdiff(m0, m1, mask_diff);  // another seed: the anti-aliased edges only
    EXPECT_EQ(cv::countNonZero(mask_diff > 128), 0) << v;
    EXPECT_LT(cv::mean(mask_diff)[0], 3.0) << v;
    for (const char* f : {"full_", "r_"}) {
      cv::Mat a = read(out / "test" / (std::string(f) + v + ".png"), cv::IMREAD_UNCHANGED);
      cv::Mat b = read(again / "test" / (std::string(f) + v + ".png"), cv::IMREAD_UNCHANGED);
      ASSERT_EQ(a.size(), b.size());
      cv::Mat diff;
      cv::absdiff(a, b, diff);
      const cv::Scalar d = cv::mean(diff);
      EXPECT_GT(d[0] + d[1] + d[2], 0.0) << f << v << ": another seed and sample count render other noise";
      EXPECT_LT(d[0] + d[1] + d[2], 3 * 12.0) << f << v << ": the same scene";
    }
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
