// The embedded default scene (resources/default_scene, made by `goris synth`, see its README) loads with
// the data set loader: 40 train / 20 test views at 128x128 with object and glossy masks and full_ images.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "core/io/dataset.h"
#include "tests/support/test_support.h"

TEST(DefaultScene, LoadsWithMasksAndFullImages) {
  auto dir = goris::test::resource_dir() / "default_scene";
  goris::Dataset d = goris::load_dataset(dir);
  EXPECT_EQ(d.format, "nerf-synthetic");
  ASSERT_EQ(d.train.size(), 40u);
  ASSERT_EQ(d.test.size(), 20u);
  for (const auto* split : {&d.train, &d.test})
    for (const auto& v : *split) {
      EXPECT_EQ(v.camera.width, 128) << v.name;
      EXPECT_EQ(v.camera.height, 128) << v.name;
      EXPECT_TRUE(v.object_mask) << v.name;
    }
  for (const auto& v : d.train) EXPECT_TRUE(v.glossy_mask) << v.name;
  for (const auto& v : d.test) EXPECT_TRUE(v.full_image) << v.name;
}

TEST(DefaultScene, MasksCoverTheTargetAndTheTable) {
  auto dir = goris::test::resource_dir() / "default_scene";
  goris::Dataset d = goris::load_dataset(dir);
  ASSERT_FALSE(d.train.empty());
  int seen = 0;
  for (const auto& v : d.train) {
    goris::Image mask = goris::load_view_object_mask(v), gloss = goris::load_view_glossy_mask(v);
    ASSERT_EQ(mask.width, 128);
    ASSERT_EQ(gloss.channels, 1);
    cv::Mat m = cv::imread(v.object_mask->string(), cv::IMREAD_GRAYSCALE);
    cv::Mat g = cv::imread(v.glossy_mask->string(), cv::IMREAD_GRAYSCALE);
    seen += cv::countNonZero(m > 128) > 20;
    EXPECT_GT(cv::countNonZero(g > 128), 128 * 128 / 10) << v.name;  // the table fills a good part of the view
  }
  EXPECT_GE(seen, 30);  // the target is visible in most training views
}
