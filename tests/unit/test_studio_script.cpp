// The editor's script language (ui/script/script.h): every action parses to what the runner needs, comments and
// blank lines are skipped with line numbers kept, and every mistake names the file and the line.
#include <fstream>

#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "ui/script/script.h"

using namespace goris;
using namespace goris::ui;
using Kind = ScriptAction::Kind;

namespace {

// The message of the goris::Error that parsing `text` throws ("" when it does not throw).
std::string parse_error(const std::string& text) {
  try {
    parse_script(text, "s.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StudioScript, ParsesEveryAction) {
  const auto a = parse_script(
      "# a comment\n"
      "\n"
      "open /data/my scene\n"
      "out \"/runs/with space\"\n"
      "set random_init_points 3000\n"
      "set background [1, 1, 1]\n"
      "train 30\n"
      "channel main depth\n"
      "channel 3 f0\n"
      "snap 2\n"
      "snap 4 test\n"
      "click 120.5 80\n"
      "compare slider 0.25\n"
      "compare off\n"
      "screenshot out/grid.png\n"
      "  wait_frames 3  \n"
      "quit\n",
      "s.txt");
  ASSERT_EQ(a.size(), 15u);
  EXPECT_EQ(a[0].kind, Kind::Open);
  EXPECT_EQ(a[0].path, "/data/my scene");
  EXPECT_EQ(a[0].line, 3);
  EXPECT_EQ(a[1].kind, Kind::Out);
  EXPECT_EQ(a[1].path, "/runs/with space");
  EXPECT_EQ(a[2].kind, Kind::Set);
  EXPECT_EQ(a[2].key, "random_init_points");
  EXPECT_EQ(a[2].value, "3000");
  EXPECT_EQ(a[3].value, "[1, 1, 1]");
  EXPECT_EQ(a[4].kind, Kind::Train);
  EXPECT_EQ(a[4].count, 30);
  EXPECT_EQ(a[5].kind, Kind::Channel);
  EXPECT_EQ(a[5].viewport, -1);
  EXPECT_EQ(a[5].channel, Channel::Depth);
  EXPECT_EQ(a[6].viewport, 3);
  EXPECT_EQ(a[6].channel, Channel::Fresnel);
  EXPECT_EQ(a[7].kind, Kind::Snap);
  EXPECT_EQ(a[7].camera, 2);
  EXPECT_FALSE(a[7].test_split);
  EXPECT_TRUE(a[8].test_split);
  EXPECT_EQ(a[9].kind, Kind::Click);
  EXPECT_FLOAT_EQ(a[9].x, 120.5f);
  EXPECT_FLOAT_EQ(a[9].y, 80.0f);
  EXPECT_EQ(a[10].kind, Kind::Compare);
  EXPECT_EQ(a[10].mode, "slider");
  EXPECT_FLOAT_EQ(a[10].split, 0.25f);
  EXPECT_EQ(a[11].mode, "off");
  EXPECT_EQ(a[12].kind, Kind::Screenshot);
  EXPECT_EQ(a[12].path, "out/grid.png");
  EXPECT_EQ(a[13].kind, Kind::WaitFrames);
  EXPECT_EQ(a[13].count, 3);
  EXPECT_EQ(a[14].kind, Kind::Quit);
  EXPECT_EQ(a[14].line, 17);
  EXPECT_STREQ(action_name(Kind::WaitFrames), "wait_frames");
  // Unavailable channels parse (whether they can be shown is decided when the line runs).
  EXPECT_EQ(parse_script("channel 0 glossy\n", "s.txt")[0].channel, Channel::Glossy);
  EXPECT_TRUE(parse_script("# nothing\n\n", "s.txt").empty());
}

TEST(StudioScript, ParsesSelectionAndRemoval) {
  const auto a = parse_script(
      "select_click 40 52\n"
      "select_click 45% 60.5% add\n"
      "select_click 1 2 remove\n"
      "click 50% 10\n"
      "select_grow -0.25\n"
      "select_labels\nselect_masks\nundo\nredo\nsave_selection\n"
      "remove\nremove 10\nexpect_step_complete\ngrid 6\n"
      "remove_start 7\nremove_wait\nremove_cancel\nscreenshot_now /tmp/a b.png\npanels Selection removal\n",
      "s.txt");
  ASSERT_EQ(a.size(), 19u);
  EXPECT_EQ(a[18].kind, Kind::Panels);
  EXPECT_EQ(a[18].names, (std::vector<std::string>{"Selection", "removal"}));
  EXPECT_EQ(a[14].kind, Kind::RemoveStart);
  EXPECT_EQ(a[14].count, 7);
  EXPECT_EQ(a[15].kind, Kind::RemoveWait);
  EXPECT_EQ(a[16].kind, Kind::RemoveCancel);
  EXPECT_EQ(a[17].kind, Kind::ScreenshotNow);
  EXPECT_EQ(a[17].path, "/tmp/a b.png");
  EXPECT_EQ(a[13].kind, Kind::Grid);
  EXPECT_EQ(a[13].count, 6);
  EXPECT_EQ(a[0].kind, Kind::SelectClick);
  EXPECT_FLOAT_EQ(a[0].x, 40);
  EXPECT_FALSE(a[0].x_fraction);
  EXPECT_EQ(a[0].select_mode, "replace");
  EXPECT_FLOAT_EQ(a[1].x, 0.45f);
  EXPECT_FLOAT_EQ(a[1].y, 0.605f);
  EXPECT_TRUE(a[1].x_fraction && a[1].y_fraction);
  EXPECT_EQ(a[1].select_mode, "add");
  EXPECT_EQ(a[2].select_mode, "remove");
  EXPECT_EQ(a[3].kind, Kind::Click);
  EXPECT_TRUE(a[3].x_fraction);
  EXPECT_FALSE(a[3].y_fraction);
  EXPECT_EQ(a[4].kind, Kind::SelectGrow);
  EXPECT_FLOAT_EQ(a[4].grow, -0.25f);
  EXPECT_EQ(a[5].kind, Kind::SelectLabels);
  EXPECT_EQ(a[6].kind, Kind::SelectMasks);
  EXPECT_EQ(a[7].kind, Kind::Undo);
  EXPECT_EQ(a[8].kind, Kind::Redo);
  EXPECT_EQ(a[9].kind, Kind::SaveSelection);
  EXPECT_EQ(a[10].kind, Kind::Remove);
  EXPECT_EQ(a[10].count, 0);
  EXPECT_EQ(a[11].count, 10);
  EXPECT_EQ(a[12].kind, Kind::ExpectStepComplete);
  EXPECT_STREQ(action_name(Kind::ExpectStepComplete), "expect_step_complete");
}

TEST(StudioScript, ErrorsNameTheLine) {
  EXPECT_NE(parse_error("quit\n\nfly 3\n").find("s.txt:3: unknown action 'fly'"), std::string::npos);
  EXPECT_NE(parse_error("train\n").find("s.txt:1: train: expected 'train N'"), std::string::npos);
  EXPECT_NE(parse_error("train 3 4\n").find("s.txt:1: train: expected"), std::string::npos);
  EXPECT_NE(parse_error("train -2\n").find("outside 1.."), std::string::npos);
  EXPECT_NE(parse_error("train 2x\n").find("'2x' is not a whole number"), std::string::npos);
  EXPECT_NE(parse_error("wait_frames 1.5\n").find("not a whole number"), std::string::npos);
  EXPECT_NE(parse_error("open\n").find("s.txt:1: open: expected a path"), std::string::npos);
  EXPECT_NE(parse_error("open \"\"\n").find("expected a path"), std::string::npos);
  EXPECT_NE(parse_error("channel 9 depth\n").find("viewport 9 is outside 0..7"), std::string::npos);
  EXPECT_NE(parse_error("channel main sparkle\n").find("unknown channel 'sparkle'"), std::string::npos);
  EXPECT_NE(parse_error("snap 1 val\n").find("expected train or test"), std::string::npos);
  EXPECT_NE(parse_error("click 1\n").find("expected 'click X Y'"), std::string::npos);
  EXPECT_NE(parse_error("click a 2\n").find("X 'a' is not a number"), std::string::npos);
  EXPECT_NE(parse_error("compare wipe\n").find("unknown mode 'wipe'"), std::string::npos);
  EXPECT_NE(parse_error("compare slider 2\n").find("outside 0..1"), std::string::npos);
  EXPECT_NE(parse_error("set key\n").find("expected 'set KEY VALUE'"), std::string::npos);
  EXPECT_NE(parse_error("quit now\n").find("s.txt:1: quit: expected 'quit'"), std::string::npos);
  EXPECT_NE(parse_error("select_click 1 2 toggle\n").find("expected add or remove"), std::string::npos);
  EXPECT_NE(parse_error("select_click 120% 2\n").find("outside 0%..100%"), std::string::npos);
  EXPECT_NE(parse_error("select_click x% 2\n").find("X 'x' is not a number"), std::string::npos);
  EXPECT_NE(parse_error("select_grow 1.5\n").find("outside -1..1"), std::string::npos);
  EXPECT_NE(parse_error("select_grow\n").find("expected 'select_grow G'"), std::string::npos);
  EXPECT_NE(parse_error("undo 2\n").find("s.txt:1: undo: expected 'undo'"), std::string::npos);
  EXPECT_NE(parse_error("remove 0\n").find("outside 1.."), std::string::npos);
  EXPECT_NE(parse_error("grid 9\n").find("tile count 9 is outside 0..8"), std::string::npos);
  EXPECT_NE(parse_error("remove_cancel now\n").find("expected 'remove_cancel'"), std::string::npos);
  EXPECT_NE(parse_error("remove_start x\n").find("'x' is not a whole number"), std::string::npos);
  EXPECT_NE(parse_error("remove 5 6\n").find("expected 'remove [ITERS]'"), std::string::npos);
}

TEST(StudioScript, LoadsFiles) {
  const auto dir = test::scratch_dir("studio_script");
  std::ofstream(dir / "ok.txt") << "wait_frames 1\nquit\n";
  EXPECT_EQ(load_script(dir / "ok.txt").size(), 2u);
  try {
    load_script(dir / "missing.txt");
    FAIL() << "a missing script loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.txt: no such script file"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "bad.txt") << "wait_frames 1\nquit 2\n";
  try {
    load_script(dir / "bad.txt");
    FAIL() << "a bad script loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "bad.txt").string() + ":2: quit"), std::string::npos) << e.what();
  }
}
