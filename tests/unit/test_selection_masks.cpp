// Masks to labels: Gaussian centres vote in the object masks of the views where they are visible; occluded
// Gaussians do not vote.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/image.h"
#include "core/util/error.h"
#include "removal/selection/selection_masks.h"
#include "removal/selection/selection_preview.h"
#include "render/raster/rasterizer.h"
#include "test_selection_scene.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

using test::TestGaussian;

struct Scene {
  std::vector<TestGaussian> object;  // a 7 x 7 x 3 slab at the origin, facing the cameras (-z side)
  TestGaussian behind;               // hidden behind the slab in every view, but inside its silhouette
  TestGaussian in_front;             // in front of the slab in the middle view only
  std::vector<Camera> cams;
};

Scene scene() {
  Scene s;
  TestGaussian proto;
  proto.scale = 0.06f;
  proto.opacity = 0.95f;
  s.object = test::grid({0.0f, 0.0f, 0.0f}, 7, 7, 3, 0.1f, proto);
  s.behind = TestGaussian{{0.0f, 0.0f, 0.6f}, 0.05f, 0.9f};
  s.in_front = TestGaussian{{0.0f, 0.0f, -1.0f}, 0.05f, 0.9f};
  for (float x : {0.0f, 1.5f, -1.5f}) s.cams.push_back(test::look_at({x, 0.0f, -4.0f}, {0.0f, 0.0f, 0.0f}));
  return s;
}

// The object's silhouette in a view: the object alone rendered, alpha > 0.5.
Image silhouette(const std::vector<TestGaussian>& object, const Camera& cam) {
  GaussianModel m = test::make_model(object);
  const RasterOutput r = rasterize(m.view(false), cam, RasterSettings{}, Device::CPU);
  Image mask(cam.width, cam.height, 1);
  const std::vector<float> a = r.gbuffer.alpha.to_host();
  for (std::size_t p = 0; p < a.size(); ++p) mask.pixels[p] = a[p] > 0.5f ? 1.0f : 0.0f;
  return mask;
}

TEST(SelectionMasks, OccludedGaussiansDoNotVote) {
  const Scene s = scene();
  std::vector<TestGaussian> all = s.object;
  all.push_back(s.behind);
  all.push_back(s.in_front);
  const std::size_t behind = s.object.size(), in_front = s.object.size() + 1;
  const GaussianModel m = test::make_model(all);
  std::vector<MaskedView> views;
  for (std::size_t v = 0; v < s.cams.size(); ++v)
    views.push_back(MaskedView{"v" + std::to_string(v), s.cams[v], silhouette(s.object, s.cams[v])});

  const MaskVotes votes = labels_from_masks(m, views);
  EXPECT_EQ(votes.views, 3u);
  // Hidden in every view: no vote, not selected, although it projects inside every mask.
  EXPECT_EQ(votes.visible[behind], 0);
  EXPECT_EQ(votes.selected[behind], 0);
  // In front of the object in the middle view only: inside 1 of 3 views.
  EXPECT_EQ(votes.visible[in_front], 3);
  EXPECT_EQ(votes.inside[in_front], 1);
  EXPECT_EQ(votes.selected[in_front], 0);
  // The object's front layer (z = -0.1, facing the cameras) is selected.
  std::size_t front = 0, front_selected = 0;
  for (std::size_t i = 0; i < s.object.size(); ++i)
    if (s.object[i].pos.z < -0.05f) {
      ++front;
      front_selected += votes.selected[i];
      EXPECT_EQ(votes.inside[i], votes.visible[i]) << i;
    }
  EXPECT_EQ(front_selected, front);

  // Without the depth test the hidden Gaussian would be selected: the test above is what keeps it out.
  MaskVoteSettings no_depth;
  no_depth.depth_tolerance = 1e6f;
  const MaskVotes blind = labels_from_masks(m, views, no_depth);
  EXPECT_EQ(blind.visible[behind], 3);
  EXPECT_EQ(blind.selected[behind], 1);

  // A stricter fraction rejects what a looser one accepts.
  MaskVoteSettings third;
  third.min_fraction = 0.3f;
  EXPECT_EQ(labels_from_masks(m, views, third).selected[in_front], 1);
}

TEST(SelectionMasks, BadInputs) {
  const Scene s = scene();
  const GaussianModel m = test::make_model(s.object);
  EXPECT_THROW(labels_from_masks(m, {}), Error);
  std::vector<MaskedView> wrong, ok;
  wrong.push_back(MaskedView{"v0", s.cams[0], Image(10, 10, 1)});
  EXPECT_THROW(labels_from_masks(m, wrong), Error);
  ok.push_back(MaskedView{"v0", s.cams[0], silhouette(s.object, s.cams[0])});
  MaskVoteSettings bad;
  bad.min_fraction = 0.0f;
  EXPECT_THROW(labels_from_masks(m, ok, bad), Error);
}

TEST(SelectionMasks, LoadsMasksFromAFolderByViewName) {
  const std::filesystem::path dir = test::scratch_dir("selection_masks");
  const Scene s = scene();
  std::vector<View> views(3);
  for (int v = 0; v < 3; ++v) {
    views[std::size_t(v)].name = "r_00" + std::to_string(v);
    views[std::size_t(v)].camera = s.cams[std::size_t(v)];
    views[std::size_t(v)].source_width = 256;  // masks on disk at twice the training size
    views[std::size_t(v)].source_height = 256;
  }
  Image big(256, 256, 1);
  for (std::size_t p = 0; p < big.pixel_count(); ++p) big.pixels[p] = p % 256 < 128 ? 1.0f : 0.0f;
  save_png(dir / "mask_000.png", big);
  save_png(dir / "r_002.png", big);
  const std::vector<MaskedView> mv = load_masked_views(views, dir);
  ASSERT_EQ(mv.size(), 2u);  // r_001 has no mask
  EXPECT_EQ(mv[0].name, "r_000");
  EXPECT_EQ(mv[1].name, "r_002");
  EXPECT_EQ(mv[0].mask.width, 128);
  EXPECT_EQ(mv[0].mask.channels, 1);
  EXPECT_FLOAT_EQ(mv[0].mask.pixels[10], 1.0f);
  EXPECT_FLOAT_EQ(mv[0].mask.pixels[100], 0.0f);

  save_png(dir / "mask_001.png", Image(100, 80, 1));  // neither the source nor the training size
  EXPECT_THROW(load_masked_views(views, dir), Error);
  EXPECT_THROW(load_masked_views(views, dir / "missing"), Error);
  EXPECT_THROW(load_masked_views(views), Error);  // the views have no data-set masks
}

TEST(SelectionMasks, PreviewTintsTheSelectionAndRemovesIt) {
  const Scene s = scene();
  const GaussianModel m = test::make_model(s.object);
  const Camera& cam = s.cams[0];
  SelectionMask all(m.count(), 1), none(m.count(), 0);
  const Image sel = render_selection_preview(m, all, cam);
  const Image not_sel = render_selection_preview(m, none, cam);
  ASSERT_EQ(sel.width, 2 * cam.width);
  ASSERT_EQ(sel.height, cam.height);
  const std::size_t centre = (std::size_t(cam.height / 2) * std::size_t(sel.width) + std::size_t(cam.width / 2)) * 3;
  const std::size_t right = centre + std::size_t(cam.width) * 3;
  // Left: grey object tinted magenta where selected; right: removed (black background) or unchanged.
  EXPECT_GT(sel.pixels[centre + 0], sel.pixels[centre + 1] + 0.2f);
  EXPECT_NEAR(not_sel.pixels[centre + 0], not_sel.pixels[centre + 1], 1e-4f);
  EXPECT_LT(sel.pixels[right + 0] + sel.pixels[right + 1], 1e-3f);
  EXPECT_NEAR(not_sel.pixels[right + 1], not_sel.pixels[centre + 1], 1e-5f);
  EXPECT_THROW(render_selection_preview(m, SelectionMask(3, 1), cam), Error);
}

}  // namespace
}  // namespace goris
