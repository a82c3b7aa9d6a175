// The shared median (core/util/median.h): the upper middle element of the sorted sample, whatever the
// order it comes in, and 0 for an empty one.
#include <gtest/gtest.h>

#include <vector>

#include "core/util/median.h"

using namespace goris;

TEST(Median, UpperMiddleOfTheSortedSample) {
  EXPECT_EQ(median_of(std::vector<float>{3, 1, 2}), 2.0f);
  EXPECT_EQ(median_of(std::vector<float>{4, 1, 3, 2}), 3.0f);  // even size: the upper of the two middles
  EXPECT_EQ(median_of(std::vector<double>{-5}), -5.0);
  EXPECT_EQ(median_of(std::vector<float>{7, 7, 1, 7, 1}), 7.0f);
}

TEST(Median, EmptySampleIsZero) { EXPECT_EQ(median_of(std::vector<float>{}), 0.0f); }

TEST(Median, LeavesTheCallersSampleUntouched) {
  const std::vector<float> v{5, 4, 3, 2, 1};
  EXPECT_EQ(median_of(v), 3.0f);
  EXPECT_EQ(v, (std::vector<float>{5, 4, 3, 2, 1}));
}
