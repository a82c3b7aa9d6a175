// The editor's selection tools (ui/selection/, ui/selection/selection_session.h) on two blobs of Gaussians, red on
// the left and blue on the right: rectangles, lassos and brush strokes on the front view, spheres, boxes
// and a colour range each take their own blob; invert, grow / shrink steps, hide and lock work on the
// selection and undo walks them back; object masks written from a selection select it again; and the
// script lines parse.
#include <chrono>
#include <thread>

#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_studio_scenes.h"
#include "ui/display/display_renderer.h"
#include "ui/script/script.h"
#include "ui/selection/selection_session.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

constexpr int kPerBlob = 120;

std::size_t in_blob(const SelectionMask* m, int blob) {
  std::size_t n = 0;
  if (m)
    for (int i = blob * kPerBlob; i < (blob + 1) * kPerBlob; ++i) n += (*m)[std::size_t(i)];
  return n;
}

// Runs one edit to its end; fails the test on its error.
void run(SelectionSession& s, std::uint64_t job) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!s.finished(job)) {
    ASSERT_LT(std::chrono::steady_clock::now(), end) << "timed out waiting for selection job " << job;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_FALSE(s.job_error(job).has_value()) << *s.job_error(job);
}

ScreenRegion front_region(ScreenRegion::Kind kind, std::vector<glm::vec2> points, Through through) {
  ScreenRegion r;
  r.kind = kind;
  r.camera = test::studio_front_camera();
  r.points = std::move(points);
  r.through = through;
  r.radius = 4.0f;
  return r;
}

struct Session {
  GaussianModel model = test::studio_two_blobs(kPerBlob);
  SelectionSession s;
  Session() { s.bind(std::make_shared<const ModelSnapshot>(model, 0, RasterSettings{}), {}, "", false); }
  const SelectionMask* mask() const { return s.view().mask.get(); }
};

}  // namespace

TEST(StudioSelectionTools, GuardKeepsHiddenAndLockedOut) {
  const GaussianModel m = test::studio_two_blobs(kPerBlob);
  SelectionModel sm;
  sm.points = selection_points(m);
  sm.graph = build_selection_graph(sm.points);
  const std::size_t n = sm.points.size();
  SelectionMask all(n, 1), blob0(n, 0), first(n, 0);
  for (int i = 0; i < kPerBlob; ++i) blob0[std::size_t(i)] = 1;
  first[0] = 1;
  SelectionGuard g = guard_adding({}, blob0, /*hide=*/true);
  EXPECT_EQ(g.hidden_count, std::size_t(kPerBlob));
  g = guard_adding(g, first, /*hide=*/false);
  EXPECT_EQ(g.locked_count, 1u);
  const SelectionState s = evaluate_selection(sm, {{SelectMode::Replace, all, false, "region", "all"}}, 0.0f, g);
  EXPECT_EQ(s.selected, std::size_t(kPerBlob));  // blob 1 only
  EXPECT_EQ(in_blob(s.mask.get(), 0), 0u);
  EXPECT_EQ(s.guard.hidden_count, std::size_t(kPerBlob));
  SelectionGuard wrong;
  wrong.locked = std::make_shared<const SelectionMask>(3, 1);
  EXPECT_THROW(evaluate_selection(sm, {}, 0.0f, wrong), Error);
}

TEST(StudioSelectionTools, ScreenRegionsTakeWhatTheyCover) {
  Session t;
  using K = ScreenRegion::Kind;
  // The left half of the view: blob 0. Through the depth only its front (the blob is opaque), through
  // everything all of it.
  run(t.s, t.s.screen_region(front_region(K::Rect, {{0, 0}, {24, 40}}, Through::Visible), SelectMode::Replace));
  const std::size_t front = in_blob(t.mask(), 0);
  EXPECT_GT(front, 0u);
  EXPECT_LT(front, std::size_t(kPerBlob / 2));
  EXPECT_EQ(in_blob(t.mask(), 1), 0u);
  run(t.s, t.s.screen_region(front_region(K::Rect, {{0, 0}, {24, 40}}, Through::All), SelectMode::Replace));
  EXPECT_GT(in_blob(t.mask(), 0), std::size_t(kPerBlob * 0.9));
  EXPECT_EQ(in_blob(t.mask(), 1), 0u);
  // A lasso around blob 1 added: both.
  run(t.s, t.s.screen_region(front_region(K::Polygon, {{28, 5}, {46, 5}, {46, 35}, {28, 35}}, Through::All),
                             SelectMode::Add));
  EXPECT_GT(in_blob(t.mask(), 1), std::size_t(kPerBlob * 0.9));
  EXPECT_GT(in_blob(t.mask(), 0), std::size_t(kPerBlob * 0.9));
  // A brush stroke down the middle of blob 0 removed: a band of it goes.
  const std::size_t before = in_blob(t.mask(), 0);
  run(t.s, t.s.screen_region(front_region(K::Brush, {{11.5f, 0}, {11.5f, 40}}, Through::All), SelectMode::Remove));
  EXPECT_LT(in_blob(t.mask(), 0), before);
  EXPECT_GT(in_blob(t.mask(), 1), std::size_t(kPerBlob * 0.9));
  // A lasso of two points is refused, and nothing changes.
  const std::size_t selected = t.s.view().selected;
  const std::uint64_t bad = t.s.screen_region(front_region(K::Polygon, {{0, 0}, {5, 5}}, Through::All), SelectMode::Add);
  while (!t.s.finished(bad)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(t.s.job_error(bad).has_value());
  EXPECT_EQ(t.s.view().selected, selected);
}

TEST(StudioSelectionTools, VolumesColourInvertStepsHideLockAndUndo) {
  Session t;
  VolumeRegion sphere;
  sphere.centre = {-1, 0, 0};
  sphere.radius = 0.6f;
  run(t.s, t.s.volume(sphere, SelectMode::Replace));
  EXPECT_GT(in_blob(t.mask(), 0), std::size_t(kPerBlob * 0.9));
  EXPECT_EQ(in_blob(t.mask(), 1), 0u);
  VolumeRegion box;
  box.kind = VolumeRegion::Kind::Box;
  box.centre = {1, 0, 0};
  box.half_extent = glm::vec3(0.5f);
  box.rotation_degrees = {0, 0, 45};
  run(t.s, t.s.volume(box, SelectMode::Replace));
  EXPECT_EQ(in_blob(t.mask(), 0), 0u);
  EXPECT_GT(in_blob(t.mask(), 1), std::size_t(kPerBlob * 0.9));
  const std::size_t boxed = t.s.view().selected;

  // Invert: the rest; undo: the box again.
  run(t.s, t.s.invert());
  EXPECT_EQ(t.s.view().selected, t.s.view().total - boxed);
  run(t.s, t.s.undo());
  EXPECT_EQ(t.s.view().selected, boxed);
  // On the core of blob 1, a shrink step takes from the border, a grow step adds (within blob 1: the blobs
  // do not touch); undo walks back.
  VolumeRegion core = sphere;
  core.centre = {1, 0, 0};
  core.radius = 0.2f;
  run(t.s, t.s.volume(core, SelectMode::Replace));
  const std::size_t cored = t.s.view().selected;
  run(t.s, t.s.step(-1));
  const std::size_t shrunk = t.s.view().selected;
  EXPECT_LT(shrunk, cored);
  run(t.s, t.s.step(1));
  EXPECT_GT(t.s.view().selected, shrunk);
  EXPECT_EQ(in_blob(t.mask(), 0), 0u);
  run(t.s, t.s.undo());
  run(t.s, t.s.undo());
  EXPECT_EQ(t.s.view().selected, cored);
  run(t.s, t.s.undo());
  EXPECT_EQ(t.s.view().selected, boxed);

  // Red: blob 0 (its base colour is about (0.92, 0.5, 0.08)).
  run(t.s, t.s.colour({0.92f, 0.5f, 0.08f}, 0.1f, SelectMode::Replace));
  EXPECT_EQ(in_blob(t.mask(), 0), std::size_t(kPerBlob));
  EXPECT_EQ(in_blob(t.mask(), 1), 0u);

  // Hide blob 0: nothing selected, 120 hidden, and no edit selects them; undo shows them again.
  run(t.s, t.s.hide_selected());
  EXPECT_EQ(t.s.view().selected, 0u);
  EXPECT_EQ(t.s.view().hidden_count, std::size_t(kPerBlob));
  ASSERT_NE(t.s.view().hidden, nullptr);
  run(t.s, t.s.invert());
  EXPECT_EQ(in_blob(t.mask(), 0), 0u);
  EXPECT_EQ(in_blob(t.mask(), 1), std::size_t(kPerBlob));
  // A click where blob 0 was finds nothing: the picker looks through hidden Gaussians.
  const std::uint64_t miss = t.s.click(test::studio_front_camera(), 11.5f, 20.5f, SelectMode::Replace);
  while (!t.s.finished(miss)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(t.s.job_error(miss).has_value());
  EXPECT_NE(t.s.job_error(miss)->find("nothing there"), std::string::npos) << *t.s.job_error(miss);
  run(t.s, t.s.undo());
  run(t.s, t.s.undo());
  EXPECT_EQ(t.s.view().hidden_count, 0u);
  EXPECT_EQ(in_blob(t.mask(), 0), std::size_t(kPerBlob));

  // Lock blob 0: a sphere around it selects nothing until it is unlocked.
  run(t.s, t.s.lock_selected());
  EXPECT_EQ(t.s.view().locked_count, std::size_t(kPerBlob));
  run(t.s, t.s.volume(sphere, SelectMode::Replace));
  EXPECT_EQ(t.s.view().selected, 0u);
  run(t.s, t.s.unlock_all());
  EXPECT_GT(in_blob(t.mask(), 0), std::size_t(kPerBlob * 0.9));
}

TEST(StudioSelectionTools, HiddenGaussiansAreNotDrawn) {
  const auto snap = std::make_shared<const ModelSnapshot>(test::studio_two_blobs(kPerBlob), 0, RasterSettings{});
  auto hidden = std::make_shared<SelectionMask>(snap->count(), 0);
  for (int i = 0; i < kPerBlob; ++i) (*hidden)[std::size_t(i)] = 1;  // blob 0, the left one
  DisplayRenderer r;
  const Camera cam = test::studio_front_camera();
  const DisplayFrame all = r.render(*snap, cam, nullptr), shown = r.render(*snap, cam, nullptr, hidden);
  auto alpha_at = [&](const DisplayFrame& f, int x) { return f.alpha[std::size_t(20 * f.width + x)]; };
  EXPECT_GT(alpha_at(all, 11), 0.5f);
  EXPECT_LT(alpha_at(shown, 11), 0.01f);  // blob 0 is gone
  EXPECT_NEAR(alpha_at(shown, 36), alpha_at(all, 36), 1e-4f);  // blob 1 as it was
}

TEST(StudioSelectionTools, TargetMasksSelectTheSelectionAgain) {
  Session t;
  VolumeRegion sphere;
  sphere.centre = {1, 0, 0};
  sphere.radius = 0.6f;
  run(t.s, t.s.volume(sphere, SelectMode::Replace));
  const fs::path dir = test::scratch_dir("studio_target_masks");
  View v;
  v.name = "r_000";
  v.camera = test::studio_front_camera();
  run(t.s, t.s.target_masks({v}, dir));
  EXPECT_TRUE(fs::exists(dir / "mask_000.png"));
  // One view votes for what it sees of blob 1 (its front), closed by their hull.
  EXPECT_GT(in_blob(t.mask(), 1), std::size_t(kPerBlob / 5));
  EXPECT_EQ(in_blob(t.mask(), 0), 0u);
  EXPECT_EQ(t.s.view().parts.size(), 1u);
}

TEST(StudioSelectionTools, ScriptLinesParse) {
  using Kind = ScriptAction::Kind;
  const auto a = parse_script(
      "select_rect 10% 20% 30 40 add\n"
      "select_polygon 1 2 3 4 5 6 remove\n"
      "select_brush 2% 50% 50% 60% 50%\n"
      "select_through all\n"
      "select_sphere 0 0 0.1 0.3\n"
      "select_box 0 0 0 1 2 3 0 0 45 add\n"
      "select_colour 0.5 0.4 0.3 0.1\n"
      "select_tool lasso\n"
      "invert\ngrow_step\nshrink_step 3\nhide\nlock\nunhide\nunlock\n"
      "use_as_target_masks /tmp/masks dir\nuse_as_target_masks\nexpect_selected 3 7\n"
      "drag 10% 10% 20 30 alt\n",
      "t.txt");
  ASSERT_EQ(a.size(), 19u);
  EXPECT_EQ(a[18].kind, Kind::Drag);
  EXPECT_EQ(a[18].modifier, "alt");
  EXPECT_EQ(a[18].coords.size(), 4u);
  EXPECT_EQ(a[0].kind, Kind::SelectRect);
  ASSERT_EQ(a[0].coords.size(), 4u);
  EXPECT_TRUE(a[0].coords[0].fraction);
  EXPECT_FLOAT_EQ(a[0].coords[1].value, 0.2f);
  EXPECT_FALSE(a[0].coords[2].fraction);
  EXPECT_EQ(a[0].select_mode, "add");
  EXPECT_EQ(a[1].coords.size(), 6u);
  EXPECT_EQ(a[1].select_mode, "remove");
  EXPECT_TRUE(a[2].radius.fraction);
  EXPECT_FLOAT_EQ(a[2].radius.value, 0.02f);
  EXPECT_EQ(a[2].coords.size(), 4u);
  EXPECT_EQ(a[3].what, "all");
  EXPECT_EQ(a[4].values.size(), 4u);
  EXPECT_EQ(a[5].values.size(), 9u);
  EXPECT_EQ(a[5].select_mode, "add");
  EXPECT_EQ(a[6].kind, Kind::SelectColour);
  EXPECT_EQ(a[7].what, "lasso");
  EXPECT_EQ(a[9].count, 1);
  EXPECT_EQ(a[10].count, 3);
  EXPECT_EQ(a[15].path, "/tmp/masks dir");
  EXPECT_TRUE(a[16].path.empty());
  EXPECT_EQ(a[17].count, 3);
  EXPECT_EQ(a[17].count_max, 7);
  for (const char* bad : {"select_rect 1 2 3\n", "select_polygon 1 2 3 4\n", "select_brush 0 1 2\n",
                          "select_sphere 0 0 0 -1\n", "select_box 0 0 0 1 1\n", "select_through some\n",
                          "select_tool wand\n", "invert now\n", "expect_selected 5 2\n", "grow_step 0\n",
                          "drag 1 2\n", "drag 1 2 3 4 super\n"})
    EXPECT_THROW(parse_script(bad, "t.txt"), Error) << bad;
}

TEST(StudioSelectionTools, ToolBarHandleAndTwoClickLinesParse) {
  using Kind = ScriptAction::Kind;
  const auto a = parse_script(
      "press Grow step\n"
      "press volume Select\n"
      "drag_handle radius 20 -5\n"
      "drag_handle x 10 0 shift\n"
      "two_click start\ntwo_click start 7\ntwo_click view 3\ntwo_click click 40% 52\ntwo_click offered\n"
      "two_click take_back 2\ntwo_click undo\ntwo_click cancel\ntwo_click use 10\ntwo_click expect review\n",
      "t.txt");
  ASSERT_EQ(a.size(), 14u);
  EXPECT_EQ(a[0].kind, Kind::Press);
  EXPECT_EQ(a[0].text, "Grow step");
  EXPECT_EQ(a[1].text, "volume Select");
  EXPECT_EQ(a[2].kind, Kind::DragHandle);
  EXPECT_EQ(a[2].what, "radius");
  ASSERT_EQ(a[2].values.size(), 2u);
  EXPECT_FLOAT_EQ(a[2].values[1], -5.0f);
  EXPECT_EQ(a[3].modifier, "shift");
  EXPECT_EQ(a[4].kind, Kind::TwoClick);
  EXPECT_EQ(a[4].what, "start");
  EXPECT_EQ(a[4].count, -1);
  EXPECT_EQ(a[5].count, 7);
  EXPECT_EQ(a[6].count, 3);
  EXPECT_TRUE(a[7].x_fraction);
  EXPECT_FLOAT_EQ(a[7].x, 0.4f);
  EXPECT_FALSE(a[7].y_fraction);
  EXPECT_EQ(a[9].count, 2);
  EXPECT_EQ(a[12].count, 10);
  EXPECT_EQ(a[13].text, "review");
  for (const char* bad : {"press\n", "drag_handle top 1 2\n", "drag_handle radius 1\n", "two_click\n",
                          "two_click jump\n", "two_click view\n", "two_click take_back 0\n", "two_click click 1\n",
                          "two_click expect later\n", "two_click undo now\n"})
    EXPECT_THROW(parse_script(bad, "t.txt"), Error) << bad;
}
