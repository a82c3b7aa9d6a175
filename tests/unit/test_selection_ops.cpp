// The selection kit: volumes, colour range, invert, combinations, graph dilation / shrinking, screen regions
// through the depth or through everything, and object masks from a selection, each on a small scene whose
// expected set is known exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/util/error.h"
#include "removal/selection/selection_grow.h"
#include "removal/selection/selection_ops.h"
#include "removal/selection/selection_region.h"
#include "removal/selection/selection_screen.h"
#include "removal/selection/selection_view_masks.h"
#include "render/raster/rasterizer.h"
#include "test_selection_scene.h"

namespace goris {
namespace {

using test::TestGaussian;

std::set<std::size_t> members(const SelectionMask& m) {
  std::set<std::size_t> s;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m[i]) s.insert(i);
  return s;
}

SelectionPoints points_at(const std::vector<glm::vec3>& pos, const std::vector<glm::vec3>& colours = {}) {
  SelectionPoints p;
  p.position = pos;
  p.scale.assign(pos.size(), 0.01f);
  p.color = colours.empty() ? std::vector<glm::vec3>(pos.size(), glm::vec3(0.5f)) : colours;
  p.label.assign(pos.size(), 0.0f);
  return p;
}

TEST(SelectionOps, SphereAndBox) {
  const SelectionPoints p = points_at({{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0.5f, 0.5f, 0}, {3, 3, 3}, {0, 0, -1}});
  EXPECT_EQ(members(select_sphere(p, {0, 0, 0}, 1.0f)), (std::set<std::size_t>{0, 1, 3, 5}));
  EXPECT_EQ(members(select_sphere(p, {0, 0, 0}, 0.9f)), (std::set<std::size_t>{0, 3}));
  EXPECT_EQ(members(select_sphere(p, {3, 3, 3}, 0.0f)), (std::set<std::size_t>{4}));
  EXPECT_THROW(select_sphere(p, {0, 0, 0}, -1.0f), Error);

  SelectionBox box;
  box.centre = {0, 0, 0};
  box.half_extent = {1.0f, 0.6f, 0.1f};
  EXPECT_EQ(members(select_box(p, box)), (std::set<std::size_t>{0, 1, 3}));
  // Turned 90 degrees about z the long axis runs along y: (0, 2) is still out, (1, 0) now out.
  box.rotation = rotation_from_euler_degrees({0, 0, 90});
  box.half_extent = {2.0f, 0.6f, 0.1f};
  EXPECT_EQ(members(select_box(p, box)), (std::set<std::size_t>{0, 2, 3}));
  // 45 degrees: a thin box along the diagonal holds (0.5, 0.5) and the origin only.
  box.rotation = rotation_from_euler_degrees({0, 0, 45});
  box.half_extent = {1.0f, 0.05f, 0.1f};
  EXPECT_EQ(members(select_box(p, box)), (std::set<std::size_t>{0, 3}));
  box.half_extent = {-1.0f, 1.0f, 1.0f};
  EXPECT_THROW(select_box(p, box), Error);
}

TEST(SelectionOps, ColourInvertAndCombine) {
  const SelectionPoints p = points_at({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}},
                                      {{1, 0, 0}, {0.9f, 0.1f, 0}, {0, 1, 0}, {0.5f, 0.5f, 0.5f}});
  EXPECT_EQ(members(select_by_colour(p, {1, 0, 0}, 0.2f)), (std::set<std::size_t>{0, 1}));
  EXPECT_EQ(members(select_by_colour(p, {1, 0, 0}, 0.0f)), (std::set<std::size_t>{0}));
  const SelectionMask a{1, 1, 0, 0}, b{0, 1, 1, 0};
  EXPECT_EQ(members(invert_selection(a)), (std::set<std::size_t>{2, 3}));
  EXPECT_EQ(members(combine_selections(a, b, Combine::Union)), (std::set<std::size_t>{0, 1, 2}));
  EXPECT_EQ(members(combine_selections(a, b, Combine::Subtract)), (std::set<std::size_t>{0}));
  EXPECT_EQ(members(combine_selections(a, b, Combine::Intersect)), (std::set<std::size_t>{1}));
  EXPECT_THROW(combine_selections(a, SelectionMask{1}, Combine::Union), Error);
  EXPECT_EQ(combine_from_name("subtract"), Combine::Subtract);
  EXPECT_THROW(combine_from_name("xor"), Error);
}

TEST(SelectionOps, DilateAndShrinkByGraphSteps) {
  // A row of centres 1 apart with k = 1: the graph is the path 0 - 1 - ... - 9.
  std::vector<glm::vec3> pos;
  for (int i = 0; i < 10; ++i) pos.push_back({float(i), 0, 0});
  const SelectionPoints p = points_at(pos);
  const SelectionGraph g = build_selection_graph(p, 1);
  SelectionMask m(10, 0);
  m[4] = m[5] = 1;
  EXPECT_EQ(members(dilate_selection(g, m, 1)), (std::set<std::size_t>{3, 4, 5, 6}));
  EXPECT_EQ(members(dilate_selection(g, m, 2)), (std::set<std::size_t>{2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(members(dilate_selection(g, m, 0)), (std::set<std::size_t>{4, 5}));
  const SelectionMask wide = dilate_selection(g, m, 2);
  EXPECT_EQ(members(shrink_selection(g, wide, 1)), (std::set<std::size_t>{3, 4, 5, 6}));
  EXPECT_EQ(members(shrink_selection(g, wide, 3)), (std::set<std::size_t>{}));
  EXPECT_THROW(dilate_selection(g, SelectionMask(3, 0), 1), Error);
  EXPECT_THROW(dilate_selection(g, m, -1), Error);
}

TEST(SelectionOps, PolygonsParseAndContain) {
  const ScreenPolygon tri = parse_polygon("0,0,10,0,0,10", "--polygon");
  ASSERT_EQ(tri.size(), 3u);
  EXPECT_TRUE(inside_polygon(tri, {2, 2}));
  EXPECT_FALSE(inside_polygon(tri, {6, 6}));
  EXPECT_THROW(parse_polygon("0,0,10,0", "--polygon"), Error);
  EXPECT_THROW(parse_polygon("0,0,10,0,1", "--polygon"), Error);
  EXPECT_THROW(parse_polygon("0,0,10,x,1,1", "--polygon"), Error);
  const ScreenPolygon r = rect_polygon({10, 20}, {0, 5});
  EXPECT_TRUE(inside_polygon(r, {5, 10}));
  EXPECT_FALSE(inside_polygon(r, {5, 21}));
  const ScreenPolygon d = disc_polygon({50, 50}, 10);
  EXPECT_TRUE(inside_polygon(d, {57, 50}));
  EXPECT_FALSE(inside_polygon(d, {58, 58}));
  EXPECT_EQ(through_from_name("all"), Through::All);
  EXPECT_THROW(through_from_name("front"), Error);
}

// Two 7 x 7 slabs 0.1 apart in x and y, one at z = -0.5 (in front), one at z = +0.5 (hidden behind it),
// seen from (0, 0, -4) (see look_at: the image's right is -x, its down is -y).
struct Slabs {
  std::vector<TestGaussian> gs;
  Camera cam = test::look_at({0, 0, -4}, {0, 0, 0});
};
Slabs slabs() {
  Slabs s;
  TestGaussian proto;
  proto.scale = 0.06f;
  proto.opacity = 0.95f;
  s.gs = test::grid({0, 0, -0.5f}, 7, 7, 1, 0.1f, proto);
  const auto back = test::grid({0, 0, 0.5f}, 7, 7, 1, 0.1f, proto);
  s.gs.insert(s.gs.end(), back.begin(), back.end());
  return s;
}

TEST(SelectionRegion, RectangleThroughTheDepthOrThroughEverything) {
  const Slabs s = slabs();
  const GaussianModel m = test::make_model(s.gs);
  const SelectionPoints pts = selection_points(m);
  // u in (60, 76): columns x = 0 and -0.1 of the front slab (u = 64 - 300 x / 3.5: 64, 72.6); the back
  // slab's centres sit further in (u = 64 - 300 x / 4.5), x = 0 and -0.1 too (64, 70.7). Same for v, y.
  const ScreenPolygon rect = rect_polygon({60, 60}, {76, 76});
  std::set<std::size_t> front, both;
  for (std::size_t i = 0; i < s.gs.size(); ++i) {
    const glm::vec3 q = s.gs[i].pos;
    if (q.x > -0.15f && q.x < 0.05f && q.y > -0.15f && q.y < 0.05f) {
      both.insert(i);
      if (q.z < 0.0f) front.insert(i);
    }
  }
  ASSERT_EQ(front.size(), 4u);
  ASSERT_EQ(both.size(), 8u);
  EXPECT_EQ(members(select_in_view_region(m, pts, s.cam, rect, Through::Visible)), front);
  EXPECT_EQ(members(select_in_view_region(m, pts, s.cam, rect, Through::All)), both);
  // A lasso (quadrilateral) around the same four front centres, through the depth.
  const ScreenPolygon lasso{{59, 59}, {78, 61}, {77, 77}, {61, 78}};
  EXPECT_EQ(members(select_in_view_region(m, pts, s.cam, lasso, Through::Visible)), front);
}

TEST(SelectionViewMasks, CoverageWithTheDepthTest) {
  const Slabs s = slabs();
  const GaussianModel m = test::make_model(s.gs);
  const std::size_t half = s.gs.size() / 2;
  SelectionMask back(m.count(), 0), front(m.count(), 0);
  for (std::size_t i = 0; i < m.count(); ++i) (i < half ? front : back)[i] = 1;
  // The back slab is hidden behind the front one in this view: its mask is empty, the front's is the
  // front slab's silhouette (alpha > 0.5 of the front slab rendered alone).
  const Mask mb = selection_view_mask(m, back, s.cam);
  EXPECT_EQ(count_set(mb), 0u);
  const Mask mf = selection_view_mask(m, front, s.cam);
  GaussianModel alone = test::make_model(std::vector<TestGaussian>(s.gs.begin(), s.gs.begin() + long(half)));
  const std::vector<float> a = rasterize(alone.view(false), s.cam, RasterSettings{}, Device::CPU)
                                   .gbuffer.alpha.to_host();
  Mask sil(s.cam.width, s.cam.height);
  for (std::size_t p = 0; p < a.size(); ++p) sil.data[p] = a[p] > 0.5f ? 255 : 0;
  EXPECT_GT(count_set(sil), 1000u);
  EXPECT_GT(mask_iou(mf, sil), 0.98);
  // Seen from behind the roles swap.
  const Camera behind = test::look_at({0, 0, 4}, {0, 0, 0});
  EXPECT_EQ(count_set(selection_view_mask(m, front, behind)), 0u);
  EXPECT_GT(count_set(selection_view_mask(m, back, behind)), 1000u);
  EXPECT_THROW(selection_view_mask(m, SelectionMask(3, 1), s.cam), Error);
}

TEST(SelectionViewMasks, FaintSelectionCutAtHalfItsPeak) {
  const Slabs s = slabs();
  const Camera behind = test::look_at({0, 0, 4}, {0, 0, 0});
  const Camera away = test::look_at({0, 0, -4}, {0, 0, -8});  // sees neither slab
  // A solid selection: the same masks as selection_view_mask in every view, at the setting's threshold.
  GaussianModel m = test::make_model(s.gs);
  const std::size_t half = s.gs.size() / 2;
  SelectionMask front(m.count(), 0);
  for (std::size_t i = 0; i < half; ++i) front[i] = 1;
  const std::vector<Camera> cams{s.cam, behind, away};
  std::size_t calls = 0;
  const SelectionViewMasks solid = selection_view_masks(m, front, cams, {}, {}, [&](std::size_t) { ++calls; });
  EXPECT_EQ(calls, cams.size());
  ASSERT_EQ(solid.masks.size(), cams.size());
  EXPECT_FALSE(solid.lowered);
  EXPECT_FLOAT_EQ(solid.threshold, 0.5f);
  EXPECT_GT(solid.peak, 0.9f);
  for (std::size_t v = 0; v < cams.size(); ++v)
    EXPECT_EQ(solid.masks[v].data, selection_view_mask(m, front, cams[v]).data) << "view " << v;
  EXPECT_GT(count_set(solid.masks[0]), 1000u);

  // The front slab made of faint Gaussians: its coverage stays under 0.5 everywhere, so selection_view_mask is
  // empty in every view; the masks are cut at half its peak and cover the slab where it is seen.
  std::vector<TestGaussian> faint = s.gs;
  for (std::size_t i = 0; i < half; ++i) faint[i].opacity = 0.08f;
  m = test::make_model(faint);
  for (const Camera& c : cams) EXPECT_EQ(count_set(selection_view_mask(m, front, c)), 0u);
  const SelectionViewMasks fog = selection_view_masks(m, front, cams);
  EXPECT_TRUE(fog.lowered);
  EXPECT_GT(fog.peak, 0.05f);
  EXPECT_LT(fog.peak, 0.5f);
  EXPECT_FLOAT_EQ(fog.threshold, 0.5f * fog.peak);
  EXPECT_GT(count_set(fog.masks[0]), 500u);
  EXPECT_NE(fog.masks[0].data[64 * 128 + 64], 0);  // the slab's centre
  EXPECT_GT(mask_iou(fog.masks[0], solid.masks[0]), 0.5);
  EXPECT_EQ(count_set(fog.masks[2]), 0u);

  // A selection no view sees keeps its empty masks.
  const SelectionViewMasks unseen = selection_view_masks(m, front, {away});
  EXPECT_FALSE(unseen.lowered);
  EXPECT_FLOAT_EQ(unseen.peak, 0.0f);
  EXPECT_EQ(count_set(unseen.masks[0]), 0u);
}

TEST(SelectionViewMasks, IouAndFileNames) {
  Mask a(4, 1), b(4, 1);
  a.data = {255, 255, 0, 0};
  b.data = {0, 255, 255, 0};
  EXPECT_DOUBLE_EQ(mask_iou(a, b), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(mask_iou(Mask(4, 1), Mask(4, 1)), 1.0);
  EXPECT_THROW(mask_iou(a, Mask(2, 2)), Error);
  EXPECT_EQ(object_mask_file_name("r_012"), "mask_012.png");
  EXPECT_EQ(object_mask_file_name("IMG_3"), "IMG_3.png");
}

}  // namespace
}  // namespace goris
