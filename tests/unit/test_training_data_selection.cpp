// The stability bench's data switches (use_glossy_masks, use_object_masks, max_train_views) applied to the
// embedded scene's training views.
#include <gtest/gtest.h>

#include "core/io/dataset.h"
#include "train/setup/training_setup.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

Dataset scene() { return load_dataset(test::resource_dir() / "default_scene"); }

TEST(TrainingDataSelection, DefaultsKeepEverything) {
  Dataset d = scene();
  const std::size_t n = d.train.size();
  ASSERT_GE(n, 8u);
  select_training_data(TrainConfig{}, d);
  EXPECT_EQ(d.train.size(), n);
  for (const View& v : d.train) {
    EXPECT_TRUE(v.glossy_mask.has_value());
    EXPECT_TRUE(v.object_mask.has_value());
  }
}

TEST(TrainingDataSelection, DropsMasksAndSpreadsTheSubset) {
  Dataset d = scene();
  const std::vector<View> all = d.train;
  TrainConfig c;
  c.input.use_glossy_masks = false;
  c.input.max_train_views = 4;
  select_training_data(c, d);
  ASSERT_EQ(d.train.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(d.train[i].image, all[i * all.size() / 4].image) << "view " << i << " is not evenly spread";
    EXPECT_FALSE(d.train[i].glossy_mask.has_value());
    EXPECT_TRUE(d.train[i].object_mask.has_value());
  }
  c = TrainConfig{};
  c.input.use_object_masks = false;
  c.input.max_train_views = 1;
  d = scene();
  select_training_data(c, d);
  ASSERT_EQ(d.train.size(), 1u);
  EXPECT_EQ(d.train[0].image, all[0].image);
  EXPECT_FALSE(d.train[0].object_mask.has_value());
  EXPECT_TRUE(d.train[0].glossy_mask.has_value());
}

TEST(TrainingDataSelection, NegativeViewCountIsAnError) {
  TrainConfig c;
  c.input.max_train_views = -1;
  EXPECT_THROW(c.validate("test"), Error);
}

}  // namespace
}  // namespace goris
