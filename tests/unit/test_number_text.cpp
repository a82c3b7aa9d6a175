// Numbers typed by a person never wrap and are refused with their limits: `--set`, config.json and the
// command-line flags' checks.
#include <gtest/gtest.h>

#include <string>

#include "core/util/number_text.h"
#include "tests/support/test_support.h"
#include "train/config/train_config.h"

namespace goris {
namespace {

std::string whole_error(const std::string& text, long double min, long double max) {
  long double v = 0;
  return parse_whole_number(text, min, max, v);
}

TEST(NumberText, WholeNumbersNeverWrap) {
  long double v = 0;
  EXPECT_EQ(parse_whole_number("42", 0, 100, v), "");
  EXPECT_EQ(v, 42);
  EXPECT_EQ(parse_whole_number("18446744073709551615", 0, 18446744073709551615.0L, v), "");
  EXPECT_EQ(whole_error("-1", 0, 18446744073709551615.0L), "must be a whole number from 0 to 18446744073709551615, got '-1'");
  EXPECT_NE(whole_error("10000000000", 1, 2147483647).find("to 2147483647"), std::string::npos);
  EXPECT_NE(whole_error("010x", 0, 100), "");  // not a number
  EXPECT_NE(whole_error("0x10", 0, 100), "");  // no hex
  EXPECT_NE(whole_error("1.5", 0, 100), "");
  EXPECT_NE(whole_error("", 0, 100), "");
  EXPECT_EQ(whole_error("010", 0, 100), "");  // decimal 10, not octal 8
}

TEST(NumberText, RealNumbersAreFinite) {
  double v = 0;
  EXPECT_EQ(parse_real_number("0.25", 0, 1, v), "");
  EXPECT_EQ(v, 0.25);
  EXPECT_NE(parse_real_number("nan", 0, 1, v).find("NaN"), std::string::npos);
  EXPECT_NE(parse_real_number("-Inf", 0, 1, v).find("NaN and infinity are not allowed"), std::string::npos);
  EXPECT_NE(parse_real_number("1e999", 0, 1e30, v), "");
  EXPECT_EQ(parse_real_number("2", 0, 1, v), "must be a number from 0 to 1, got '2'");
}

TEST(NumberText, SettingsAreRangeChecked) {
  TrainConfig c;
  test::expect_error([&] { apply_config_overrides({"random_init_points=10000000000"}, c); }, "2147483647");
  test::expect_error([&] { apply_config_overrides({"random_init_points=10000000000"}, c); }, "random_init_points");
  TrainConfig huge;
  apply_config_overrides({"random_init_points=900000000"}, huge);  // fits an int, but not in memory
  test::expect_error([&] { huge.validate("training options"); }, "from 1 to " + std::to_string(kMaxRandomInitPoints));
  test::expect_error([&] { apply_config_overrides({"seed=-1"}, c); }, "from 0 to 18446744073709551615");
  test::expect_error([&] { apply_config_overrides({"lambda_ssim=nan"}, c); }, "NaN");
  test::expect_error([&] { apply_config_overrides({"iterations=2.5"}, c); }, "whole number");
  test::expect_error([&] { apply_config_overrides({"lambda_ssim=abc"}, c); }, "must be a number");
  apply_config_overrides({"random_init_points=5000", "seed=7"}, c);
  EXPECT_EQ(c.init.random_points, 5000);
  EXPECT_EQ(c.seed, 7u);
}

}  // namespace
}  // namespace goris
