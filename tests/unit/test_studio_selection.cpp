// The editor's selection (ui/selection/selection_edit.h, ui/selection/selection_session.h) on two separate
// blobs of Gaussians, a red one left and a blue one right: a click grows over its own blob only, shift
// adds, ctrl removes, the slider regrows and shrinks, undo / redo walk every edit (a drag being one step),
// labels select, saving writes a selection.json that `goris remove` accepts for this model, and another
// model clears it.
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "core/util/error.h"
#include "removal/selection/selection_file.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_studio_scenes.h"
#include "ui/selection/selection_session.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

constexpr int kPerBlob = 150;

GaussianModel two_blobs() { return test::studio_two_blobs(kPerBlob); }

// Blob 0 projects to u ~ 11.5, blob 1 to u ~ 36.5.
Camera front_camera() { return test::studio_front_camera(); }

std::size_t in_blob(const SelectionMask& m, int blob) {
  std::size_t n = 0;
  for (int i = blob * kPerBlob; i < (blob + 1) * kPerBlob; ++i) n += m[std::size_t(i)];
  return n;
}

SelectionMask one_hot(std::size_t n, std::size_t i) {
  SelectionMask m(n, 0);
  m[i] = 1;
  return m;
}

void wait_for(SelectionSession& s, std::uint64_t job) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!s.finished(job)) {
    ASSERT_LT(std::chrono::steady_clock::now(), end) << "timed out waiting for selection job " << job;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

TEST(StudioSelection, EditsComposeOverTheKnnGraph) {
  const GaussianModel m = two_blobs();
  SelectionModel sm;
  sm.points = selection_points(m);
  sm.graph = build_selection_graph(sm.points);
  const std::size_t n = m.count();

  // A click grows over its own blob, never across the gap to the other.
  SelectionState a = evaluate_selection(sm, {{SelectMode::Replace, one_hot(n, 3), true, "click", "a"}}, 0.6f);
  ASSERT_NE(a.mask, nullptr);
  EXPECT_GT(in_blob(*a.mask, 0), std::size_t(kPerBlob * 0.8));
  EXPECT_EQ(in_blob(*a.mask, 1), 0u);
  EXPECT_EQ(a.selected, in_blob(*a.mask, 0));
  // Slider 0: just the clicked Gaussian.
  const SelectionState single = evaluate_selection(sm, a.parts, 0.0f);
  EXPECT_EQ(single.selected, 1u);
  // Shift-click adds the other blob; ctrl-click on it removes it again.
  std::vector<SelectionPart> parts = a.parts;
  parts.push_back({SelectMode::Add, one_hot(n, kPerBlob + 5), true, "click", "b"});
  const SelectionState both = evaluate_selection(sm, parts, 0.6f);
  EXPECT_GT(in_blob(*both.mask, 1), std::size_t(kPerBlob * 0.8));
  EXPECT_EQ(in_blob(*both.mask, 0), in_blob(*a.mask, 0));
  parts.push_back({SelectMode::Remove, one_hot(n, kPerBlob + 7), true, "click", "c"});
  const SelectionState removed = evaluate_selection(sm, parts, 0.6f);
  EXPECT_EQ(in_blob(*removed.mask, 1), 0u);
  EXPECT_EQ(*removed.mask, *a.mask);
  // A replace drops what came before.
  parts.push_back({SelectMode::Replace, one_hot(n, kPerBlob + 9), true, "click", "d"});
  const SelectionState replaced = evaluate_selection(sm, parts, 0.6f);
  EXPECT_EQ(replaced.parts.size(), 1u);
  EXPECT_EQ(in_blob(*replaced.mask, 0), 0u);
  // Negative slider values erode the whole selection; rules' parts do not grow.
  SelectionMask blob0(n, 0);
  for (int i = 0; i < kPerBlob; ++i) blob0[std::size_t(i)] = 1;
  const SelectionState rule = evaluate_selection(sm, {{SelectMode::Replace, blob0, false, "labels", "l"}}, 0.9f);
  EXPECT_EQ(rule.selected, std::size_t(kPerBlob));
  // (An isolated object has no unselected neighbour to erode from; half of one does.)
  EXPECT_EQ(evaluate_selection(sm, rule.parts, -0.5f).selected, std::size_t(kPerBlob));
  SelectionMask half(n, 0);
  for (int i = 0; i < kPerBlob; ++i) half[std::size_t(i)] = sm.points.position[std::size_t(i)].x < -1.0f;
  const std::size_t half_count = count_selected(half);
  const SelectionState shrunk = evaluate_selection(sm, {{SelectMode::Replace, half, false, "labels", "h"}}, -0.5f);
  EXPECT_LT(shrunk.selected, half_count);
  EXPECT_GT(shrunk.selected, 0u);
  EXPECT_LT(evaluate_selection(sm, shrunk.parts, -1.0f).selected, shrunk.selected);
  // A growth that would take more than half of the scene is refused, as `goris select` refuses it: blob 0
  // is 150 of 200 Gaussians here.
  SelectionModel lopsided;
  lopsided.points = sm.points;
  for (auto* v : {&lopsided.points.scale, &lopsided.points.label}) v->resize(200);
  lopsided.points.position.resize(200);
  lopsided.points.color.resize(200);
  lopsided.graph = build_selection_graph(lopsided.points);
  try {
    evaluate_selection(lopsided, {{SelectMode::Replace, one_hot(200, 3), true, "click", "the click"}}, 1.0f);
    FAIL() << "a leaking growth was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("growing 'the click' by 1.00 selects more than half"), std::string::npos)
        << e.what();
  }
  const SelectionState cleared = evaluate_selection(sm, {}, 0.5f);
  EXPECT_EQ(cleared.mask, nullptr);
  EXPECT_EQ(cleared.selected, 0u);
  EXPECT_THROW(evaluate_selection(sm, rule.parts, 1.5f), Error);
  EXPECT_THROW(evaluate_selection(sm, {{SelectMode::Add, SelectionMask(3, 1), false, "x", "x"}}, 0.0f), Error);
}

TEST(StudioSelection, HistoryUndoesRedoesAndMergesDrags) {
  SelectionHistory h(4);
  auto state = [](std::size_t n) {
    SelectionState s;
    s.selected = n;
    return s;
  };
  EXPECT_FALSE(h.can_undo());
  EXPECT_FALSE(h.undo());
  h.push(state(1));
  h.push(state(2));
  EXPECT_EQ(h.current().selected, 2u);
  // A drag: the first edit is a step, its later edits replace it.
  h.push(state(3), false);
  h.push(state(4), true);
  h.push(state(5), true);
  EXPECT_EQ(h.current().selected, 5u);
  ASSERT_TRUE(h.undo());
  EXPECT_EQ(h.current().selected, 2u);
  ASSERT_TRUE(h.redo());
  EXPECT_EQ(h.current().selected, 5u);
  EXPECT_FALSE(h.redo());
  // After an undo nothing merges into the entry below; a new edit drops the redo tail.
  ASSERT_TRUE(h.undo());
  h.push(state(6), true);
  EXPECT_EQ(h.current().selected, 6u);
  EXPECT_FALSE(h.can_redo());
  ASSERT_TRUE(h.undo());
  EXPECT_EQ(h.current().selected, 2u);
  // Bounded: the oldest entries go.
  for (std::size_t k = 10; k < 20; ++k) h.push(state(k));
  EXPECT_EQ(h.size(), 4u);
  int undos = 0;
  while (h.undo()) ++undos;
  EXPECT_EQ(undos, 3);
  EXPECT_EQ(h.current().selected, 16u);
  h.reset(state(42));
  EXPECT_FALSE(h.can_undo());
  EXPECT_EQ(h.current().selected, 42u);
}

TEST(StudioSelection, SessionClicksUndoesSavesAndRebinds) {
  const fs::path run = test::scratch_dir("studio_selection_session");
  const GaussianModel m = two_blobs();
  auto snap = std::make_shared<const ModelSnapshot>(m, 0, RasterSettings{});
  SelectionSession s;
  s.bind(snap, run, (run / "point_cloud.ply").string(), /*load_saved=*/true);  // nothing saved yet
  const Camera cam = front_camera();

  std::uint64_t job = s.click(cam, 11.5f, 20.5f, SelectMode::Replace);
  wait_for(s, job);
  ASSERT_FALSE(s.job_error(job).has_value()) << *s.job_error(job);
  SelectionView v = s.view();
  ASSERT_NE(v.mask, nullptr);
  EXPECT_GT(in_blob(*v.mask, 0), std::size_t(kPerBlob * 0.8));
  EXPECT_EQ(in_blob(*v.mask, 1), 0u);
  EXPECT_TRUE(v.can_undo);
  EXPECT_FALSE(v.saved);
  const std::size_t first = v.selected;

  job = s.click(cam, 36.5f, 20.5f, SelectMode::Add);
  wait_for(s, job);
  EXPECT_GT(in_blob(*s.view().mask, 1), std::size_t(kPerBlob * 0.8));
  // The background: an error that says so, nothing changes.
  const std::uint64_t before = s.version();
  const std::size_t both = s.view().selected;
  job = s.click(cam, 24.0f, 2.0f, SelectMode::Replace);
  wait_for(s, job);
  ASSERT_TRUE(s.job_error(job).has_value());
  EXPECT_NE(s.job_error(job)->find("nothing there"), std::string::npos) << *s.job_error(job);
  EXPECT_EQ(s.version(), before);
  EXPECT_EQ(s.view().selected, both);

  // Slider drag (three edits, one step), then undo walks back: drag, add, click, empty.
  s.set_grow(0.0f, false);
  s.set_grow(0.1f, true);
  job = s.set_grow(0.0f, true);
  wait_for(s, job);
  EXPECT_EQ(s.view().selected, 2u);  // two clicked Gaussians, ungrown
  job = s.undo();
  wait_for(s, job);
  EXPECT_GT(s.view().selected, first);
  job = s.undo();
  wait_for(s, job);
  EXPECT_EQ(s.view().selected, first);
  job = s.undo();
  wait_for(s, job);
  EXPECT_EQ(s.view().mask, nullptr);
  job = s.undo();
  wait_for(s, job);
  EXPECT_TRUE(s.job_error(job).has_value());  // nothing left to undo
  job = s.redo();
  wait_for(s, job);
  EXPECT_EQ(s.view().selected, first);

  // Labels: blob 0 (label ~0.98), closed.
  job = s.from_labels();
  wait_for(s, job);
  ASSERT_FALSE(s.job_error(job).has_value()) << *s.job_error(job);
  EXPECT_EQ(in_blob(*s.view().mask, 0), std::size_t(kPerBlob));
  EXPECT_EQ(in_blob(*s.view().mask, 1), 0u);

  // Saving: selection.json + .npy that read back against this model.
  EXPECT_EQ(s.save(), selection_json_path(run));
  EXPECT_TRUE(s.view().saved);
  const StoredSelection stored = read_selection(run, m);
  EXPECT_EQ(stored.mask, *s.view().mask);
  EXPECT_EQ(stored.record.method, "labels");

  // A new session on the same model loads it; another model starts empty (and is not given this one).
  SelectionSession again;
  again.bind(snap, run, "", true);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (again.busy() || !again.view().mask) {
    ASSERT_LT(std::chrono::steady_clock::now(), end);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(*again.view().mask, stored.mask);
  EXPECT_TRUE(again.view().saved);
  EXPECT_FALSE(again.view().can_undo);
  GaussianModel moved = two_blobs();
  moved.values(Param::Position)[0] += 0.01f;
  auto other = std::make_shared<const ModelSnapshot>(moved, 0, RasterSettings{});
  again.bind(other, run, "", true);
  while (again.busy()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(again.view().mask, nullptr);
  bool reported = false;
  for (const auto& [text, error] : again.take_messages()) reported |= text.find("not loaded") != std::string::npos;
  EXPECT_TRUE(reported) << "a saved selection of another model must be reported, not loaded";

  // Nothing selected, or no run folder: saving says why.
  s.bind(other, fs::path(), "", false);
  EXPECT_THROW(s.save(), Error);
}
