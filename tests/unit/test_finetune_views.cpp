// The fine-tune's training views of stage 2: photo losses off inside the exclusion mask, a reference view's
// inpainted targets on its hole, the lifted reference points projected into the other views (depth-tested
// against the removed surface), and a view's own 2D fill on the hole pixels no point reached, at its weight;
// the true images of a synthetic scene in place of all of them (the fills' measurement).
#include <gtest/gtest.h>

#include <vector>

#include <glm/glm.hpp>

#include "core/util/error.h"
#include "removal/lift/finetune_views.h"

namespace goris {
namespace {

constexpr int kW = 6, kH = 4;
constexpr std::size_t kHW = std::size_t(kW) * kH;

// Looks down +z from the origin: pixel (x, y) sees the point ((x + 0.5 - cx) z / f, (y + 0.5 - cy) z / f, z).
Camera straight_camera() {
  Camera c;
  c.width = kW;
  c.height = kH;
  c.fx = c.fy = 10.0f;
  c.cx = 3.0f;
  c.cy = 2.0f;
  c.R = glm::mat3(1.0f);
  c.t = glm::vec3(0.0f);
  return c;
}

glm::vec3 seen_at(int x, int y, float z) {
  return {(float(x) + 0.5f - 3.0f) * z / 10.0f, (float(y) + 0.5f - 2.0f) * z / 10.0f, z};
}

TrainView view_named(const char* name) {
  TrainView v;
  v.name = name;
  v.camera = straight_camera();
  v.image.assign(3 * kHW, 0.5f);
  v.object_mask.assign(kHW, 0.0f);
  return v;
}

// Columns 1-3 of every row: the target (photo loss off); the hole is columns 2-3.
Mask exclusion() {
  Mask m(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 1; x <= 3; ++x) m.data[std::size_t(y) * kW + x] = 255;
  return m;
}

Mask hole() {
  Mask m(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 2; x <= 3; ++x) m.data[std::size_t(y) * kW + x] = 255;
  return m;
}

MapSet flat_fill(float r, float g, float b) {
  MapSet m;
  m.rgb = Image(kW, kH, 3);
  for (std::size_t p = 0; p < kHW; ++p) {
    m.rgb.pixels[p * 3 + 0] = r;
    m.rgb.pixels[p * 3 + 1] = g;
    m.rgb.pixels[p * 3 + 2] = b;
  }
  return m;
}

// One lifted point seen at pixel (2, 1) at depth 2, coloured (0.1, 0.2, 0.3), rough.
ReferencePoints one_point() {
  ReferencePoints pts;
  pts.position.push_back(seen_at(2, 1, 2.0f));
  pts.color.push_back({0.1f, 0.2f, 0.3f});
  pts.normal.push_back({0.0f, 0.0f, -1.0f});
  pts.diffuse.push_back({0.1f, 0.2f, 0.3f});
  pts.fresnel.push_back({0.04f, 0.04f, 0.04f});
  pts.roughness.push_back(0.5f);
  pts.region.push_back(1.0f);
  pts.view.push_back(0);
  pts.pixel.push_back({2, 1});
  return pts;
}

std::size_t px(int x, int y) { return std::size_t(y) * kW + x; }

TEST(FinetuneViews, PointsFirstThenTheViewsOwnFillAtItsWeight) {
  std::vector<TrainView> views = {view_named("ref"), view_named("other"), view_named("bare")};
  const Mask ex = exclusion(), h = hole();
  const MapSet ref_maps = flat_fill(0.9f, 0.9f, 0.9f), own = flat_fill(0.6f, 0.5f, 0.4f);
  std::vector<ReferenceTargets> refs = {{&h, &ref_maps}, {&h, &own, 0.25f}};
  std::vector<FinetuneViewInputs> in(3);
  for (auto& i : in) i.exclude = &ex;
  in[0].reference = 0;
  in[1].fill = 1;
  const FinetuneViewStats st = prepare_finetune_views(views, in, refs, one_point());

  // Photo loss: off exactly inside the exclusion mask, in every view; the label loss is off.
  for (const TrainView& v : views) {
    ASSERT_EQ(v.loss_weight.size(), kHW);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) EXPECT_EQ(v.loss_weight[px(x, y)], (x >= 1 && x <= 3) ? 0.0f : 1.0f) << x << "," << y;
    EXPECT_TRUE(v.object_mask.empty());
  }
  EXPECT_EQ(st.excluded_pixels, 3u * 3 * kH);

  // The reference view: its inpainted colour on the whole hole, at weight 1.
  ASSERT_TRUE(views[0].inpaint);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool in_hole = x == 2 || x == 3;
      EXPECT_EQ(views[0].inpaint->appearance_weight[px(x, y)], in_hole ? 1.0f : 0.0f);
      if (in_hole) EXPECT_FLOAT_EQ(views[0].inpaint->color[px(x, y)], 0.9f);
    }

  // The other view: the point at (2, 1) with weight 1, its own fill on the rest of the hole at 0.25, nothing
  // at the excluded pixels outside the hole.
  const InpaintTargets& t = *views[1].inpaint;
  EXPECT_FLOAT_EQ(t.appearance_weight[px(2, 1)], 1.0f);
  EXPECT_FLOAT_EQ(t.color[0 * kHW + px(2, 1)], 0.1f);
  EXPECT_FLOAT_EQ(t.color[2 * kHW + px(2, 1)], 0.3f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (x == 2 && y == 1) continue;
      const bool in_hole = x == 2 || x == 3;
      EXPECT_FLOAT_EQ(t.appearance_weight[px(x, y)], in_hole ? 0.25f : 0.0f) << x << "," << y;
      if (in_hole) {
        EXPECT_FLOAT_EQ(t.color[0 * kHW + px(x, y)], 0.6f);
        EXPECT_FLOAT_EQ(t.color[1 * kHW + px(x, y)], 0.5f);
        EXPECT_FLOAT_EQ(t.color[2 * kHW + px(x, y)], 0.4f);
      }
    }

  // A view without a fill of its own: the point alone.
  const InpaintTargets& b = *views[2].inpaint;
  for (std::size_t p = 0; p < kHW; ++p) EXPECT_EQ(b.appearance_weight[p], p == px(2, 1) ? 1.0f : 0.0f);

  EXPECT_EQ(st.projected_points, 2u);
  EXPECT_EQ(st.filled_pixels, 2u * kH - 1);
  EXPECT_EQ(st.appearance_pixels, 2u * kH + (2u * kH - 1));
}

TEST(FinetuneViews, APointBehindTheRemovedSurfaceIsHiddenAndTheFillTakesItsPixel) {
  std::vector<TrainView> views = {view_named("other")};
  const Mask ex = exclusion(), h = hole();
  const MapSet own = flat_fill(0.6f, 0.5f, 0.4f);
  Image depth(kW, kH, 1);
  for (std::size_t p = 0; p < kHW; ++p) depth.pixels[p] = 1.0f;  // the kept surface at z = 1, the point at 2
  std::vector<ReferenceTargets> refs = {{&h, &own, 0.5f}};
  std::vector<FinetuneViewInputs> in(1);
  in[0].exclude = &ex;
  in[0].removed_depth = &depth;
  in[0].fill = 0;
  const FinetuneViewStats st = prepare_finetune_views(views, in, refs, one_point());
  EXPECT_EQ(st.projected_points, 0u);
  EXPECT_FLOAT_EQ(views[0].inpaint->appearance_weight[px(2, 1)], 0.5f);
  EXPECT_FLOAT_EQ(views[0].inpaint->color[px(2, 1)], 0.6f);
}

TEST(FinetuneViews, NoPointsAndNoFillLeaveAViewWithoutTargets) {
  std::vector<TrainView> views = {view_named("other")};
  const Mask ex = exclusion();
  std::vector<FinetuneViewInputs> in(1);
  in[0].exclude = &ex;
  prepare_finetune_views(views, in, {}, ReferencePoints{});
  EXPECT_FALSE(views[0].inpaint);
}

TEST(FinetuneViews, AFillOfAnotherSizeIsRefusedByTheViewsName) {
  std::vector<TrainView> views = {view_named("other")};
  const Mask ex = exclusion(), small(kW - 1, kH);
  const MapSet own = flat_fill(0.6f, 0.5f, 0.4f);
  std::vector<ReferenceTargets> refs = {{&small, &own, 1.0f}};
  std::vector<FinetuneViewInputs> in(1);
  in[0].exclude = &ex;
  in[0].fill = 0;
  try {
    prepare_finetune_views(views, in, refs, ReferencePoints{});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("other"), std::string::npos) << e.what();
  }
}

TEST(FinetuneViews, TrueFillsReplaceEveryMadeUpPixelAndNothingElse) {
  // A reference view (targets on the hole) and a view with a lifted point: after use_true_fills every pixel
  // whose photo loss was off or that had a target learns the true image under the photo loss; the rest keeps
  // its photo; no inpainting target is left.
  std::vector<TrainView> views = {view_named("ref"), view_named("other")};
  const Mask ex = exclusion(), h = hole();
  const MapSet ref_maps = flat_fill(0.9f, 0.9f, 0.9f);
  std::vector<ReferenceTargets> refs = {{&h, &ref_maps}};
  std::vector<FinetuneViewInputs> in(2);
  for (auto& i : in) i.exclude = &ex;
  in[0].reference = 0;
  prepare_finetune_views(views, in, refs, one_point());
  ASSERT_TRUE(views[0].inpaint && views[1].inpaint);
  std::vector<std::vector<float>> truth(2, std::vector<float>(3 * kHW));
  for (std::size_t i = 0; i < 3 * kHW; ++i) truth[0][i] = truth[1][i] = 0.01f * float(i % 97);
  EXPECT_EQ(use_true_fills(views, truth), 2 * 3 * std::size_t(kH));  // columns 1-3 of both views
  for (const TrainView& v : views) {
    EXPECT_FALSE(v.inpaint) << v.name;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const std::size_t p = px(x, y);
        EXPECT_EQ(v.loss_weight[p], 1.0f) << v.name << " " << x << "," << y;
        const bool made_up = ex.data[p] != 0;
        for (std::size_t c = 0; c < 3; ++c)
          EXPECT_EQ(v.image[c * kHW + p], made_up ? truth[0][c * kHW + p] : 0.5f) << v.name << " " << x << "," << y;
      }
  }
}

TEST(FinetuneViews, ATrueImageOfAnotherSizeIsRefusedByTheViewsName) {
  std::vector<TrainView> views = {view_named("other")};
  const Mask ex = exclusion();
  std::vector<FinetuneViewInputs> in(1);
  in[0].exclude = &ex;
  prepare_finetune_views(views, in, {}, ReferencePoints{});
  try {
    use_true_fills(views, {std::vector<float>(3 * kHW - 3, 0.0f)});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("other"), std::string::npos) << e.what();
  }
  EXPECT_THROW(use_true_fills(views, {}), Error);  // one image per view
}

TEST(FinetuneViews, PhotoTargetsAgainstTheTruthSplitByWhatTheRemovalChanged) {
  // One view: the truth is 0.5 everywhere; the photo is 0.8 on column 0 (the target's shadow, trained on) and
  // on columns 1-3 (the target itself, photo loss off). The removal relit column 0 to 0.6 and dereflected
  // column 4 from 0.5 to 0.4 (a wrong change); column 5 is untouched and right.
  std::vector<TrainView> views = {view_named("v")};
  const Mask ex = exclusion();
  std::vector<FinetuneViewInputs> in(1);
  in[0].exclude = &ex;
  prepare_finetune_views(views, in, {}, ReferencePoints{});
  std::vector<float> photo(3 * kHW, 0.5f), truth(3 * kHW, 0.5f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x <= 3; ++x)
      for (std::size_t c = 0; c < 3; ++c) photo[c * kHW + px(x, y)] = 0.8f;
  views[0].image = photo;
  for (int y = 0; y < kH; ++y)
    for (std::size_t c = 0; c < 3; ++c) {
      views[0].image[c * kHW + px(0, y)] = 0.6f;
      views[0].image[c * kHW + px(4, y)] = 0.4f;
    }
  const PhotoTargetsTruthError e = photo_targets_against_truth(views, {photo}, {truth});
  EXPECT_NEAR(e.imprint, 4 * kH * 0.3, 1e-5);         // columns 0-3
  EXPECT_EQ(e.trained_pixels, 3 * std::size_t(kH));   // columns 0, 4, 5
  EXPECT_NEAR(e.photos, kH * 0.3, 1e-5);              // column 0 as taken
  EXPECT_NEAR(e.targets, kH * (0.1 + 0.1), 1e-5);     // column 0 relit, column 4 made wrong
  EXPECT_EQ(e.changed_pixels, 2 * std::size_t(kH));
  EXPECT_NEAR(e.changed_photos, kH * 0.3, 1e-5);
  EXPECT_NEAR(e.changed_targets, kH * 0.2, 1e-5);
  EXPECT_THROW(photo_targets_against_truth(views, {photo}, {std::vector<float>(3)}), Error);
  EXPECT_THROW(photo_targets_against_truth(views, {}, {truth}), Error);
}

}  // namespace
}  // namespace goris
