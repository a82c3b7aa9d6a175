// A stage's record of what it was made from: equal inputs match, any difference is named, and a missing or
// broken record never counts as a match.
#include <gtest/gtest.h>

#include <fstream>

#include "core/io/made_from.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

nlohmann::json inputs() {
  return {{"stage1", {{"source", "checkpoints/iter_00000060.ckpt"}, {"model", "00ab"}}},
          {"selection", {{"gaussians", 12}, {"fingerprint", "ffee"}}},
          {"options", {{"inpainter", "telea"}, {"ablate", nlohmann::json::array()}}}};
}

TEST(MadeFrom, SameInputsMatch) {
  const auto dir = test::scratch_dir("made_from_same");
  write_made_from(dir / "made_from.json", inputs());
  EXPECT_EQ(made_from_changes(dir / "made_from.json", inputs()), "");
}

TEST(MadeFrom, ChangesAreNamed) {
  const auto dir = test::scratch_dir("made_from_changes");
  write_made_from(dir / "made_from.json", inputs());
  nlohmann::json now = inputs();
  now["selection"]["fingerprint"] = "0001";
  now["options"]["inpainter"] = "ns";
  now["iterations"] = 20;  // a key the record lacks
  EXPECT_EQ(made_from_changes(dir / "made_from.json", now), "iterations, options.inpainter, selection.fingerprint");
}

TEST(MadeFrom, MissingOrBrokenRecordNeverMatches) {
  const auto dir = test::scratch_dir("made_from_missing");
  EXPECT_EQ(made_from_changes(dir / "made_from.json", inputs()), "no record of what it was made from");
  std::ofstream(dir / "made_from.json") << "{ not json";
  EXPECT_EQ(made_from_changes(dir / "made_from.json", inputs()), "no record of what it was made from");
}

}  // namespace
}  // namespace goris
