// The generalization suite's scenes (every axis the removal depends on is covered, every scene is a valid
// `goris synth` scene) and its summary: goals from the per-scene results, regressions against a committed one.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <set>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/bench/bench_suite.h"
#include "core/util/error.h"

using namespace goris::bench;
namespace fs = std::filesystem;

TEST(BenchSuite, GeneralizationCoversEveryAxisWithValidScenes) {
  const auto& scenes = suite_scenes("generalization");
  EXPECT_GE(scenes.size(), 12u);
  std::set<std::string> names, materials, shapes, targets, elevations, kinds, presets;
  std::set<double> roughness;
  for (const auto& s : scenes) {
    EXPECT_TRUE(names.insert(s.name).second) << "duplicate " << s.name;
    EXPECT_NO_THROW(goris::synth::make_scene(s.synth)) << s.name;
    kinds.insert(s.kind), presets.insert(s.synth.preset);
    if (s.synth.table_material) materials.insert(*s.synth.table_material);
    if (s.synth.preset == "marble") materials.insert("marble");
    if (s.synth.table_shape) shapes.insert(*s.synth.table_shape);
    if (s.synth.target_shape) targets.insert(*s.synth.target_shape);
    if (s.synth.camera_elevation) elevations.insert(*s.synth.camera_elevation);
    if (s.synth.table_roughness) roughness.insert(*s.synth.table_roughness);
  }
  int glossy = 0;
  for (const auto& s : scenes) glossy += s.kind == "glossy";
  EXPECT_GE(glossy, 10);
  EXPECT_EQ(materials, (std::set<std::string>{"dielectric", "marble", "metal"}));
  EXPECT_EQ(shapes, (std::set<std::string>{"floor", "rect", "round"}));
  EXPECT_EQ(targets, (std::set<std::string>{"convex", "holed", "small", "tall", "thin"}));
  EXPECT_TRUE(elevations.count("low") && elevations.count("high"));
  EXPECT_TRUE(presets.count("lambert-room") && presets.count("lambert-ground") && presets.count("twin-mirrors") &&
              presets.count("occluded"));
  EXPECT_LE(*roughness.begin(), 0.01);
  EXPECT_GE(*roughness.rbegin(), 0.35);
}

TEST(BenchSuite, TheHeldOutScenesAreGlossyAndNoneIsInTheGeneralizationSuite) {
  // The held-out scenes judge a choice made on the generalization suite: neither a name nor a seed may be shared.
  const auto& held = suite_scenes("heldout");
  EXPECT_EQ(held.size(), 4u);
  for (const auto& h : held) {
    EXPECT_EQ(h.kind, "glossy") << h.name;
    EXPECT_NO_THROW(goris::synth::make_scene(h.synth)) << h.name;
    for (const auto& s : suite_scenes("generalization")) {
      EXPECT_NE(h.name, s.name);
      EXPECT_NE(h.synth.seed, s.synth.seed) << h.name << " and " << s.name;
    }
  }
}

TEST(BenchSuite, FastIsASubsetAndUnknownSuitesAreNamed) {
  const auto& all = suite_scenes("generalization");
  const auto& fast = suite_scenes("fast");
  EXPECT_EQ(fast.size(), 3u);
  for (const auto& f : fast) {
    bool found = false;
    for (const auto& s : all) found = found || (s.name == f.name && s.kind == f.kind);
    EXPECT_TRUE(found) << f.name;
  }
  try {
    suite_scenes("nope");
    FAIL();
  } catch (const goris::Error& e) {
    EXPECT_NE(std::string(e.what()).find("generalization"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("heldout"), std::string::npos) << e.what();
  }
}

namespace {
SuiteResult result(const std::string& scene, const std::string& kind, const std::string& config, double region,
                   double ghost, double psnr = 25, double seconds = 100) {
  SuiteResult r;
  r.scene = scene, r.kind = kind, r.config = config, r.ok = true;
  r.region_psnr = region, r.ghost_ratio = ghost, r.psnr = psnr, r.seconds = seconds;
  r.region_ssim = 0.8, r.region_flip = 0.1, r.flip = 0.05;
  return r;
}
}  // namespace

TEST(BenchSuite, SummaryGivesMeanWorstAndGoals) {
  std::vector<SuiteResult> rs = {
      result("a", "glossy", "baseline", 20, 0.6), result("a", "glossy", "default", 25, 0.1),
      result("b", "glossy", "baseline", 22, 0.5), result("b", "glossy", "default", 23.5, 0.2),
      result("room", "lambertian", "baseline", 30, 0.1, 28, 100), result("room", "lambertian", "default", 30, 0.1, 27.9, 110),
  };
  SuiteSummary s = summarize_suite("generalization", "medium", rs, "baseline");
  const auto& g = s.json["goals"]["default"];
  EXPECT_NEAR(g["mean_region_gain_db"].get<double>(), 3.25, 1e-9);
  EXPECT_NEAR(g["worst_region_gain_db"].get<double>(), 1.5, 1e-9);
  EXPECT_EQ(g["worst_region_gain_scene"], "b");
  EXPECT_NEAR(g["worst_ghost_ratio"].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(g["lambertian_worst_time_ratio"].get<double>(), 1.1, 1e-9);
  EXPECT_TRUE(g["meets_goals"].get<bool>());
  EXPECT_NE(s.markdown.find("| a | glossy | default |"), std::string::npos) << s.markdown;

  EXPECT_TRUE(g["worst_ghost_above_floor"].is_null());  // no floor measured: no distance above it
  rs[1].ghost_floor = 0.05, rs[3].ghost_floor = 0.15;  // a's ghost 0.1 is 0.05 above its floor, b's 0.2 as well
  rs[3].ghost_ratio = 0.25;
  const SuiteSummary f = summarize_suite("generalization", "medium", rs, "baseline");
  EXPECT_NEAR(f.json["goals"]["default"]["worst_ghost_above_floor"].get<double>(), 0.1, 1e-9);
  EXPECT_EQ(f.json["goals"]["default"]["worst_ghost_above_floor_scene"], "b");
  EXPECT_NE(f.markdown.find("| 0.25 | 0.15 | - |"), std::string::npos) << f.markdown;  // ghost | floor | G share of b's default row
  EXPECT_NE(f.markdown.find("| +0.10 (b) |"), std::string::npos) << f.markdown;
  rs[3].stage1_glossy_share = 0.42;  // an intrinsic stage 1 whose glossy term carries 42 % of the glossy surface
  const SuiteSummary gs = summarize_suite("generalization", "medium", rs, "baseline");
  EXPECT_NE(gs.markdown.find("| 0.25 | 0.15 | 0.42 |"), std::string::npos) << gs.markdown;
  EXPECT_NEAR(gs.json["rows"][3]["stage1_glossy_share"].get<double>(), 0.42, 1e-9);
  EXPECT_TRUE(gs.json["rows"][2]["stage1_glossy_share"].is_null());  // b's baseline: a radiance stage 1
  rs[3].ghost_ratio = 0.3;  // a ghost left on one scene fails the goals
  EXPECT_FALSE(summarize_suite("generalization", "medium", rs, "baseline").json["goals"]["default"]["meets_goals"].get<bool>());
  rs[3].ghost_ratio = 0.2;
  rs[5].seconds = 130;  // the Lambertian scene at 1.3x the baseline's time fails them too
  EXPECT_FALSE(summarize_suite("generalization", "medium", rs, "baseline").json["goals"]["default"]["meets_goals"].get<bool>());
  rs[5].seconds = 110;
  rs[1].ok = false;  // a failed glossy scene: the goals are not met (the mean would skip it)
  const auto partial = summarize_suite("generalization", "medium", rs, "baseline").json["goals"]["default"];
  EXPECT_EQ(partial["glossy_measured"].get<int>(), 1);
  EXPECT_FALSE(partial["meets_goals"].get<bool>());
}

TEST(BenchSuite, RegressionsAreDropsBeyondTheTolerance) {
  std::vector<SuiteResult> before = {result("a", "glossy", "default", 25, 0.1), result("b", "glossy", "default", 23, 0.2)};
  const auto committed = summarize_suite("fast", "short", before, "baseline").json;
  auto now = before;
  auto check = [&] { return check_suite(committed, summarize_suite("fast", "short", now, "baseline").json, 0.5); };
  now[0].region_psnr = 24.7;  // within 0.5 dB
  EXPECT_TRUE(check().regressions.empty());
  EXPECT_EQ(check().compared, 2);
  EXPECT_EQ(check().unverified, 2);  // the committed rows name no scene images
  now[1].region_psnr = 22.0;
  auto bad = check().regressions;
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_NE(bad[0].find("b / default"), std::string::npos) << bad[0];
  now[1].region_psnr = 23, now[0].ok = false;
  bad = check().regressions;
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_NE(bad[0].find("failed"), std::string::npos) << bad[0];
}

TEST(BenchSuite, ScenesRenderedDifferentlyAreNotCompared) {
  std::vector<SuiteResult> before = {result("a", "glossy", "default", 25, 0.1), result("b", "glossy", "default", 23, 0.2)};
  before[0].scene_images = "00000000000000aa", before[1].scene_images = "00000000000000bb";
  const auto committed = summarize_suite("fast", "short", before, "baseline").json;
  EXPECT_EQ(committed["rows"][0]["scene_images"], "00000000000000aa");
  auto now = before;
  now[1].region_psnr = 20;  // a drop on a scene whose images are the committed ones: a regression
  auto c = check_suite(committed, summarize_suite("fast", "short", now, "baseline").json, 0.5);
  EXPECT_EQ(c.regressions.size(), 1u);
  EXPECT_EQ(c.compared, 2);
  EXPECT_EQ(c.unverified, 0);
  now[1].scene_images = "00000000000000cc";  // the same drop on a scene rendered differently: not compared
  c = check_suite(committed, summarize_suite("fast", "short", now, "baseline").json, 0.5);
  EXPECT_TRUE(c.regressions.empty());
  EXPECT_EQ(c.compared, 1);
  ASSERT_EQ(c.not_compared.size(), 1u);
  EXPECT_NE(c.not_compared[0].find("b:"), std::string::npos) << c.not_compared[0];
  now[0].scene_images = "00000000000000dd";
  c = check_suite(committed, summarize_suite("fast", "short", now, "baseline").json, 0.5);
  EXPECT_EQ(c.compared, 0);
  EXPECT_EQ(c.not_compared.size(), 2u);
}

TEST(BenchSuite, SceneFingerprintFollowsThePixelsNotTheEncoding) {
  const fs::path dir = fs::temp_directory_path() / ("goris_scene_fp_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "train");
  fs::create_directories(dir / "test");
  cv::Mat img(8, 12, CV_8UC4, cv::Scalar(10, 20, 30, 255));
  img.at<cv::Vec4b>(3, 5) = cv::Vec4b(200, 100, 50, 128);
  cv::imwrite((dir / "train" / "r_000.png").string(), img, {cv::IMWRITE_PNG_COMPRESSION, 1});
  cv::imwrite((dir / "test" / "r_000.png").string(), img, {cv::IMWRITE_PNG_COMPRESSION, 1});
  const std::string a = scene_images_fingerprint(dir);
  EXPECT_EQ(a.size(), 16u);
  cv::imwrite((dir / "test" / "r_000.png").string(), img, {cv::IMWRITE_PNG_COMPRESSION, 9});
  EXPECT_EQ(scene_images_fingerprint(dir), a);  // the same pixels, compressed differently
  img.at<cv::Vec4b>(0, 0)[1] += 1;
  cv::imwrite((dir / "test" / "r_000.png").string(), img);
  const std::string b = scene_images_fingerprint(dir);
  EXPECT_NE(b, a);  // one channel of one pixel
  fs::copy_file(dir / "test" / "r_000.png", dir / "test" / "r_001.png");
  EXPECT_NE(scene_images_fingerprint(dir), b);  // an image more
  fs::remove_all(dir / "train");
  fs::remove_all(dir / "test");
  EXPECT_THROW(scene_images_fingerprint(dir), goris::Error);
  fs::remove_all(dir);
}
