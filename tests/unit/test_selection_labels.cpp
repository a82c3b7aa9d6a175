// Label selection (label > 0.3, outliers out, closed by the hull of the selected centres) on hand-built
// scenes: a labelled sphere shell with unlabelled Gaussians inside, a floor, strays far away.
#include <gtest/gtest.h>

#include <cmath>

#include "core/util/error.h"
#include "removal/selection/selection_labels.h"
#include "test_selection_scene.h"

namespace goris {
namespace {

using test::TestGaussian;

// Indices of the scene below.
struct ShellScene {
  std::vector<TestGaussian> g;
  std::size_t shell_begin = 0, shell_end = 0;
  std::size_t inside_a = 0, inside_b = 0;   // unlabelled Gaussians inside the shell
  std::size_t below_threshold = 0;          // label 0.25 on the shell: not a seed, but inside the hull
  std::size_t floor_begin = 0, floor_end = 0;
  std::size_t between = 0;                  // unlabelled, between the shell and the lone stray
  std::size_t stray = 0;                    // a labelled Gaussian far away
  std::size_t group_begin = 0, group_end = 0;  // a labelled stray group
};

ShellScene shell_scene() {
  ShellScene s;
  const int n = 300;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  s.shell_begin = 0;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
    TestGaussian t;
    t.pos = 0.5f * glm::vec3(float(r * std::cos(golden * i)), float(r * std::sin(golden * i)), float(z));
    t.label = 0.9f;
    t.color = glm::vec3(0.9f, 0.1f, 0.1f);
    s.g.push_back(t);
  }
  s.shell_end = s.g.size();
  auto add = [&](glm::vec3 p, float label) {
    TestGaussian t;
    t.pos = p;
    t.label = label;
    s.g.push_back(t);
    return s.g.size() - 1;
  };
  s.inside_a = add({0.0f, 0.0f, 0.0f}, 0.1f);
  s.inside_b = add({0.2f, -0.1f, 0.15f}, 0.02f);
  s.below_threshold = add({0.0f, 0.0f, -0.45f}, 0.25f);
  s.floor_begin = s.g.size();
  for (const TestGaussian& t : test::grid({0.0f, 0.0f, -1.0f}, 10, 10, 1, 0.3f, TestGaussian{})) s.g.push_back(t);
  s.floor_end = s.g.size();
  s.between = add({1.5f, 1.5f, 0.0f}, 0.05f);
  s.stray = add({3.0f, 3.0f, 0.0f}, 0.9f);
  s.group_begin = s.g.size();
  for (int i = 0; i < 12; ++i) add(glm::vec3(-3.0f, 0.0f, 0.0f) + 0.05f * glm::vec3(float(i % 3), float(i / 3 % 2), float(i / 6)), 0.8f);
  s.group_end = s.g.size();
  return s;
}

TEST(SelectionLabels, ThresholdSeedsOnlyLabelsAbove) {
  const ShellScene s = shell_scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  ASSERT_EQ(pts.size(), s.g.size());
  EXPECT_NEAR(pts.label[s.stray], 0.9f, 1e-5f);
  EXPECT_NEAR(pts.color[0].x, 0.9f, 1e-5f);
  const SelectionMask seeds = label_seeds(pts, 0.3f);
  EXPECT_EQ(count_selected(seeds), 300u + 1u + 12u);
  EXPECT_EQ(seeds[s.below_threshold], 0);
  EXPECT_EQ(label_seeds(pts, 0.2f)[s.below_threshold], 1);
  EXPECT_EQ(count_selected(label_seeds(pts, 0.95f)), 0u);

  LabelSelectSettings no_close;
  no_close.close.enabled = false;
  const SelectionResult r = select_by_label(pts, no_close);
  EXPECT_EQ(r.mask, seeds);
  EXPECT_EQ(r.summary.selected, 313u);
  EXPECT_EQ(r.summary.volume, SelectionVolume::Kind::None);
  EXPECT_THROW(select_by_label(pts, LabelSelectSettings{1.5f, {}}), Error);
}

TEST(SelectionLabels, HullClosureAddsUnlabelledInsideAndOutliersStayOut) {
  const ShellScene s = shell_scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  const SelectionResult r = select_by_label(pts);
  EXPECT_EQ(r.summary.volume, SelectionVolume::Kind::Hull);
  // Inside the shell: added although unlabelled (or below the threshold).
  EXPECT_EQ(r.mask[s.inside_a], 1);
  EXPECT_EQ(r.mask[s.inside_b], 1);
  EXPECT_EQ(r.mask[s.below_threshold], 1);
  EXPECT_EQ(r.summary.by_volume, 3u);
  // The strays are outliers: they do not shape the hull, so nothing between them and the shell is taken ...
  EXPECT_EQ(r.outliers[s.stray], 1);
  for (std::size_t i = s.group_begin; i < s.group_end; ++i) EXPECT_EQ(r.outliers[i], 1) << i;
  EXPECT_EQ(r.summary.outliers, 13u);
  EXPECT_EQ(r.mask[s.between], 0);
  for (std::size_t i = s.floor_begin; i < s.floor_end; ++i) EXPECT_EQ(r.mask[i], 0) << i;
  // ... but they keep their selection (the paper removes every Gaussian with label > 0.3).
  EXPECT_EQ(r.mask[s.stray], 1);
  EXPECT_EQ(r.summary.selected, 313u + 3u);
  for (std::size_t i = s.shell_begin; i < s.shell_end; ++i) EXPECT_EQ(r.outliers[i], 0) << i;
  EXPECT_NE(r.summary.describe("by label").find("316 of"), std::string::npos) << r.summary.describe("by label");

  // keep_outliers = false drops them.
  LabelSelectSettings drop;
  drop.close.keep_outliers = false;
  const SelectionResult rd = select_by_label(pts, drop);
  EXPECT_EQ(rd.mask[s.stray], 0);
  EXPECT_EQ(rd.summary.dropped, 13u);
  EXPECT_EQ(rd.summary.selected, 303u);

  // Without outlier removal the stray inflates the hull and swallows what lies between.
  LabelSelectSettings no_outliers;
  no_outliers.close.outliers.k = 0;
  const SelectionResult rn = select_by_label(pts, no_outliers);
  EXPECT_EQ(rn.summary.outliers, 0u);
  EXPECT_EQ(rn.mask[s.between], 1);
}

TEST(SelectionLabels, FlatSelectionFallsBackToAPaddedOrientedBox) {
  // A labelled flat patch (a poster: 5 x 5 centres in z = 0, 1-sigma 0.05) and unlabelled Gaussians near it.
  TestGaussian lab;
  lab.label = 0.9f;
  lab.scale = 0.05f;
  std::vector<TestGaussian> g = test::grid({0.0f, 0.0f, 0.0f}, 5, 5, 1, 0.1f, lab);
  auto add = [&](glm::vec3 p) {
    TestGaussian t;
    t.pos = p;
    g.push_back(t);
    return g.size() - 1;
  };
  const std::size_t just_above = add({0.1f, 0.1f, 0.03f});   // within the box's padding (0.05)
  const std::size_t well_above = add({0.1f, 0.1f, 0.3f});
  const std::size_t beside = add({0.6f, 0.0f, 0.0f});        // in the plane, beyond the patch
  const SelectionResult r = select_by_label(selection_points(test::make_model(g)));
  EXPECT_EQ(r.summary.volume, SelectionVolume::Kind::Box);
  EXPECT_EQ(r.mask[just_above], 1);
  EXPECT_EQ(r.mask[well_above], 0);
  EXPECT_EQ(r.mask[beside], 0);
  EXPECT_EQ(r.summary.by_volume, 1u);

  // A collinear set (a thin rod) falls back the same way.
  std::vector<TestGaussian> rod = test::grid({0.0f, 0.0f, 0.0f}, 8, 1, 1, 0.1f, lab);
  rod.push_back(TestGaussian{{0.0f, 0.02f, -0.02f}});
  rod.push_back(TestGaussian{{0.0f, 0.2f, 0.0f}});
  const SelectionResult rr = select_by_label(selection_points(test::make_model(rod)));
  EXPECT_EQ(rr.summary.volume, SelectionVolume::Kind::Box);
  EXPECT_EQ(rr.mask[8], 1);
  EXPECT_EQ(rr.mask[9], 0);
  // Fewer than 4 labelled Gaussians span no volume: nothing is added, even right next to them.
  TestGaussian lab2 = lab;
  lab2.pos = glm::vec3(0.1f, 0.0f, 0.0f);
  const SelectionResult r2 =
      select_by_label(selection_points(test::make_model({lab, lab2, TestGaussian{{0.05f, 0.0f, 0.01f}}})));
  EXPECT_EQ(r2.summary.volume, SelectionVolume::Kind::None);
  EXPECT_EQ(r2.summary.selected, 2u);
}

TEST(SelectionLabels, EmptyAndMismatchedInputs) {
  const SelectionPoints pts = selection_points(test::make_model({TestGaussian{}, TestGaussian{{1, 0, 0}}}));
  const SelectionResult r = select_by_label(pts);
  EXPECT_EQ(r.summary.seeds, 0u);
  EXPECT_EQ(r.summary.selected, 0u);
  EXPECT_THROW(close_selection(pts, SelectionMask(3, 0)), Error);
  const SelectionPoints none = selection_points(test::make_model({}));
  EXPECT_EQ(select_by_label(none).summary.selected, 0u);

  GaussianModel bad = test::make_model({TestGaussian{}});
  bad.values(Param::Position)[1] = NAN;
  EXPECT_THROW(selection_points(bad), Error);
}

TEST(SelectionLabels, ApplySelectionWritesConfidentLabels) {
  GaussianModel m = test::make_model({TestGaussian{}, TestGaussian{{1, 0, 0}}, TestGaussian{{2, 0, 0}}});
  apply_selection_to_labels(m, {0, 1, 0});
  const SelectionPoints pts = selection_points(m);
  EXPECT_GT(pts.label[1], 0.99f);
  EXPECT_LT(pts.label[0], 0.01f);
  EXPECT_EQ(label_seeds(pts, 0.3f), (SelectionMask{0, 1, 0}));
  EXPECT_EQ(m.values(Param::ExtraLogit)[extra::kDiffuse], 0.0f);  // other channels untouched
  EXPECT_THROW(apply_selection_to_labels(m, {1, 0}), Error);
}

}  // namespace
}  // namespace goris
