// Region growing from a clicked Gaussian and shrinking, over the centres' kNN graph, on hand-built scenes:
// a red cluster touching a blue one, a red speck across a gap, a same-coloured cluster with another label.
#include <gtest/gtest.h>

#include <random>

#include "core/util/error.h"
#include "removal/selection/selection_grow.h"
#include "test_selection_scene.h"

namespace goris {
namespace {

using test::TestGaussian;

struct Scene {
  std::vector<TestGaussian> g;
  std::size_t a_begin = 0, a_end = 0;  // red cube, 6x6x6, spacing 0.1
  std::size_t b_begin = 0, b_end = 0;  // blue cube touching A (same spacing)
  std::size_t c_begin = 0, c_end = 0;  // 3 red Gaussians 0.4 beyond A's far face (a gap of 4 spacings)
  std::size_t d_begin = 0, d_end = 0;  // red cube touching A on another side, but labelled as not the object
};

Scene scene() {
  Scene s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.03f, 0.03f);
  auto add_block = [&](glm::vec3 center, glm::vec3 color, float label) {
    TestGaussian proto;
    proto.label = label;
    for (TestGaussian t : test::grid(center, 6, 6, 6, 0.1f, proto)) {
      t.color = color + glm::vec3(jitter(rng), jitter(rng), jitter(rng));  // texture noise
      s.g.push_back(t);
    }
  };
  add_block({0.0f, 0.0f, 0.0f}, {0.8f, 0.15f, 0.1f}, 0.8f);
  s.a_end = s.g.size();
  s.b_begin = s.g.size();
  add_block({0.6f, 0.0f, 0.0f}, {0.1f, 0.2f, 0.85f}, 0.8f);  // A spans x in [-0.25, 0.25]: B starts at 0.35
  s.b_end = s.g.size();
  s.c_begin = s.g.size();
  for (int i = 0; i < 3; ++i) {
    TestGaussian t;
    t.pos = glm::vec3(-0.65f - 0.1f * float(i), 0.0f, 0.0f);  // A's face is at x = -0.25
    t.color = glm::vec3(0.8f, 0.15f, 0.1f);
    t.label = 0.8f;
    s.g.push_back(t);
  }
  s.c_end = s.g.size();
  s.d_begin = s.g.size();
  add_block({0.0f, 0.6f, 0.0f}, {0.8f, 0.15f, 0.1f}, 0.1f);
  s.d_end = s.g.size();
  return s;
}

SelectionMask one_seed(std::size_t n, std::size_t i) {
  SelectionMask m(n, 0);
  m[i] = 1;
  return m;
}

TEST(SelectionGrow, GraphIsSymmetricWithMedianSpacing) {
  const Scene s = scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  const SelectionGraph g = build_selection_graph(pts, 10);
  ASSERT_EQ(g.size(), pts.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    ASSERT_GE(g.offsets[i + 1] - g.offsets[i], 10u);
    for (std::uint32_t e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
      const std::uint32_t j = g.neighbors[e];
      ASSERT_NE(j, i);
      EXPECT_NEAR(g.distances[e], glm::length(pts.position[i] - pts.position[j]), 1e-6f);
      bool back = false;
      for (std::uint32_t f = g.offsets[j]; f < g.offsets[j + 1]; ++f) back = back || g.neighbors[f] == i;
      ASSERT_TRUE(back) << i << " -> " << j;
    }
    EXPECT_GT(g.spacing[i], 0.0f);
  }
  EXPECT_THROW(build_selection_graph(pts, 0), Error);
  EXPECT_EQ(build_selection_graph(selection_points(test::make_model({TestGaussian{}})), 10).neighbors.size(), 0u);
}

TEST(SelectionGrow, OneSeedRecoversItsClusterWithoutLeaking) {
  const Scene s = scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  const SelectionGraph graph = build_selection_graph(pts);
  for (float grow : {0.5f, 0.75f}) {
    GrowSettings gs;
    gs.grow = grow;
    const GrowResult r = grow_selection(pts, graph, one_seed(pts.size(), 100), gs);
    EXPECT_FALSE(r.hit_limit);
    EXPECT_EQ(r.seeds, 1u);
    for (std::size_t i = s.a_begin; i < s.a_end; ++i) EXPECT_EQ(r.mask[i], 1) << "A " << i << " grow " << grow;
    for (std::size_t i = s.b_begin; i < s.b_end; ++i) EXPECT_EQ(r.mask[i], 0) << "B (colour) " << i;
    for (std::size_t i = s.c_begin; i < s.c_end; ++i) EXPECT_EQ(r.mask[i], 0) << "C (gap) " << i;
    for (std::size_t i = s.d_begin; i < s.d_end; ++i) EXPECT_EQ(r.mask[i], 0) << "D (label) " << i;
    EXPECT_EQ(r.added, s.a_end - s.a_begin - 1);
  }
  // At g = 1 colour hardly matters any more (tolerance 1.5): B joins, the gap and the label still hold.
  GrowSettings full;
  full.grow = 1.0f;
  full.max_fraction = 1.0f;
  const GrowResult r1 = grow_selection(pts, graph, one_seed(pts.size(), 100), full);
  EXPECT_EQ(r1.mask[s.b_begin + 100], 1);
  for (std::size_t i = s.c_begin; i < s.c_end; ++i) EXPECT_EQ(r1.mask[i], 0) << "C (gap) " << i;
  for (std::size_t i = s.d_begin; i < s.d_end; ++i) EXPECT_EQ(r1.mask[i], 0) << "D (label) " << i;
  // The gap really is bridged by graph edges (C's few points list A's among their nearest): growing is
  // stopped by the distance test, not by the absence of edges.
  bool edge = false;
  for (std::size_t i = s.c_begin; i < s.c_end; ++i)
    for (std::uint32_t e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) edge = edge || graph.neighbors[e] < s.a_end;
  EXPECT_TRUE(edge);
}

TEST(SelectionGrow, SliderZeroAddsNothingAndSmallValuesLess) {
  const Scene s = scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  const SelectionGraph graph = build_selection_graph(pts);
  GrowSettings gs;
  gs.grow = 0.0f;
  EXPECT_EQ(grow_selection(pts, graph, one_seed(pts.size(), 100), gs).added, 0u);
  gs.grow = 0.05f;  // colour tolerance 0.025 < the texture noise
  const GrowResult small = grow_selection(pts, graph, one_seed(pts.size(), 100), gs);
  EXPECT_LT(small.added, s.a_end - s.a_begin - 1);
  gs.max_fraction = 1.5f;
  EXPECT_THROW(grow_selection(pts, graph, one_seed(pts.size(), 100), gs), Error);
  gs.max_fraction = 0.5f;
  gs.grow = -0.1f;
  EXPECT_THROW(grow_selection(pts, graph, one_seed(pts.size(), 100), gs), Error);
  EXPECT_THROW(grow_selection(pts, graph, SelectionMask(3, 1), GrowSettings{}), Error);
}

TEST(SelectionGrow, TheSliderIsMonotone) {
  // A larger grow value never selects less, from one seed (median reference) or from many (mean).
  const Scene s = scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  const SelectionGraph graph = build_selection_graph(pts);
  SelectionMask many(pts.size(), 0);
  for (std::size_t i = 0; i < 20; ++i) many[s.a_begin + 7 * i] = 1;
  for (const SelectionMask& seeds : {one_seed(pts.size(), 100), many}) {
    SelectionMask prev = seeds;
    for (int step = 1; step <= 20; ++step) {
      GrowSettings gs;
      gs.grow = 0.05f * float(step);
      gs.max_fraction = 1.0f;
      const GrowResult r = grow_selection(pts, graph, seeds, gs);
      for (std::size_t i = 0; i < prev.size(); ++i)
        if (prev[i]) ASSERT_EQ(r.mask[i], 1) << "grow " << gs.grow << " lost Gaussian " << i;
      prev = r.mask;
    }
  }
}

TEST(SelectionGrow, DeterministicAndBoundedByMaxFraction) {
  const Scene s = scene();
  const SelectionPoints pts = selection_points(test::make_model(s.g));
  const GrowResult r1 = grow_selection(pts, one_seed(pts.size(), 100));
  const GrowResult r2 = grow_selection(pts, one_seed(pts.size(), 100));
  EXPECT_EQ(r1.mask, r2.mask);

  // Everything alike: growth would take the whole scene; it stops at the limit and says so.
  std::vector<TestGaussian> same = test::grid({0, 0, 0}, 10, 10, 4, 0.1f, TestGaussian{});
  const SelectionPoints sp = selection_points(test::make_model(same));
  GrowSettings gs;
  gs.grow = 0.5f;
  gs.max_fraction = 0.25f;
  const GrowResult r = grow_selection(sp, one_seed(sp.size(), 0), gs);
  EXPECT_TRUE(r.hit_limit);
  EXPECT_EQ(r.limit, 100u);
  EXPECT_EQ(count_selected(r.mask), 100u);
  // Seeds already beyond the limit: nothing added, reported.
  const GrowResult over = grow_selection(sp, SelectionMask(sp.size(), 1), gs);
  EXPECT_TRUE(over.hit_limit);
  EXPECT_EQ(over.added, 0u);
}

TEST(SelectionGrow, ShrinkErodesTheBoundaryRing) {
  // A 10 x 10 floor, the central 6 x 6 selected; k = 8 gives the 8-neighbourhood.
  const std::vector<TestGaussian> floor = test::grid({0, 0, 0}, 10, 10, 1, 0.1f, TestGaussian{});
  const SelectionPoints pts = selection_points(test::make_model(floor));
  const SelectionGraph g = build_selection_graph(pts, 8);
  SelectionMask m(pts.size(), 0);
  for (int y = 2; y < 8; ++y)
    for (int x = 2; x < 8; ++x) m[std::size_t(y * 10 + x)] = 1;
  const SelectionMask one = shrink_selection(g, m, 1);
  EXPECT_EQ(count_selected(one), 16u);
  for (int y = 3; y < 7; ++y)
    for (int x = 3; x < 7; ++x) EXPECT_EQ(one[std::size_t(y * 10 + x)], 1) << x << "," << y;
  EXPECT_EQ(count_selected(shrink_selection(g, m, 2)), 4u);
  EXPECT_EQ(count_selected(shrink_selection(g, m, 5)), 0u);
  EXPECT_EQ(shrink_selection(g, m, 0), m);
  // Growing the shrunk selection back over the uniform floor restores (at least) the patch.
  GrowSettings gs;
  gs.grow = 0.3f;
  gs.max_fraction = 1.0f;
  const GrowResult back = grow_selection(pts, g, one, gs);
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m[i]) EXPECT_EQ(back.mask[i], 1) << i;

  // An isolated cluster (no unselected neighbour in the graph) does not shrink.
  const Scene s = scene();
  const SelectionPoints sp = selection_points(test::make_model(s.g));
  const SelectionGraph sg = build_selection_graph(sp);
  SelectionMask all_but_c(sp.size(), 1);
  for (std::size_t i = s.c_begin; i < s.c_end; ++i) all_but_c[i] = 0;
  SelectionMask only_c(sp.size(), 0);
  for (std::size_t i = s.c_begin; i < s.c_end; ++i) only_c[i] = 1;
  // C's points are linked to A (see above), so they erode; the whole scene minus C erodes only at C's
  // neighbours.
  EXPECT_EQ(count_selected(shrink_selection(sg, only_c, 1)), 0u);
  EXPECT_GT(count_selected(shrink_selection(sg, all_but_c, 1)), sp.size() - 3 - 40);
  EXPECT_EQ(shrink_selection(sg, SelectionMask(sp.size(), 1), 3), SelectionMask(sp.size(), 1));
  EXPECT_THROW(shrink_selection(sg, SelectionMask(2, 1), 1), Error);
}

}  // namespace
}  // namespace goris
