// Emit weights from the glossy masks (train/loop/emit_weights.h, intrinsic_emit = mask): a Gaussian that
// projects onto the glossy mask does not emit, one beside it does, one no view sees keeps 1, and views
// without a mask do not vote. After a removal the masks are filled under the target
// (removal/masks/removed_glossy_masks.h), so what the lift places there takes the surface's vote.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <nlohmann/json.hpp>

#include "removal/masks/removed_glossy_masks.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_selection_scene.h"
#include "train/config/train_config.h"
#include "train/loop/emit_weights.h"
#include "train/setup/auto_mode.h"

namespace goris {
namespace {

TEST(EmitWeights, GlossyMaskVotesPerGaussian) {
  // Camera at (0, -5, 0) looking at the origin: world x is image right, world z is image up.
  const Camera cam = test::look_at({0.0f, -5.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 64, 64, 60.0f);
  std::vector<test::TestGaussian> gs(3);
  gs[0].pos = {-1.0f, 0.0f, 0.0f};  // left half of the image: glossy
  gs[1].pos = {1.0f, 0.0f, 0.0f};   // right half: rough
  gs[2].pos = {0.0f, -10.0f, 0.0f}; // behind the camera: no view sees it
  const GaussianModel model = test::make_model(gs);

  TrainView glossy_left;
  glossy_left.camera = cam;
  glossy_left.glossy_mask.assign(64 * 64, 0.0f);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 32; ++x) glossy_left.glossy_mask[std::size_t(y) * 64 + std::size_t(x)] = 1.0f;
  TrainView no_mask;  // a view without a glossy mask does not vote
  no_mask.camera = cam;
  TrainView half = glossy_left;  // a second masked view where everything is half glossy
  std::fill(half.glossy_mask.begin(), half.glossy_mask.end(), 0.5f);

  std::vector<float> w = glossy_mask_emit_weights(model, {glossy_left, no_mask});
  ASSERT_EQ(w.size(), 3u);
  EXPECT_FLOAT_EQ(w[0], 0.0f);
  EXPECT_FLOAT_EQ(w[1], 1.0f);
  EXPECT_FLOAT_EQ(w[2], 1.0f);
  w = glossy_mask_emit_weights(model, {glossy_left, half});  // the mean over the views that see it
  EXPECT_FLOAT_EQ(w[0], 0.25f);
  EXPECT_FLOAT_EQ(w[1], 0.75f);
}

TEST(EmitWeights, RemovedTargetTakesTheSurroundingGlossyValue) {
  // Camera at (0, -5, 0) looking at the origin, world z up. The glossy table fills the image's lower half;
  // the photo's mask marks the target standing on it (x in [24, 40), y in [40, 56)) as not glossy, and a
  // second blob on the table's far edge (x in [44, 56), y in [26, 38)) straddles table and background.
  const int n = 64;
  const Camera cam = test::look_at({0.0f, -5.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, n, n, 60.0f);
  TrainView view;
  view.name = "r_000";
  view.camera = cam;
  view.glossy_mask.assign(std::size_t(n) * n, 0.0f);
  for (int y = 32; y < n; ++y)
    for (int x = 0; x < n; ++x) view.glossy_mask[std::size_t(y) * n + x] = 1.0f;
  InpaintMaskView hole;
  hole.covered = Mask(n, n);
  for (int y = 40; y < 56; ++y)
    for (int x = 24; x < 40; ++x) {
      view.glossy_mask[std::size_t(y) * n + x] = 0.0f;
      hole.covered.set(x, y, true);
    }
  for (int y = 26; y < 38; ++y)
    for (int x = 44; x < 56; ++x) {
      if (y >= 32) view.glossy_mask[std::size_t(y) * n + x] = 0.0f;
      hole.covered.set(x, y, true);
    }
  const std::vector<float> before = view.glossy_mask;

  // A Gaussian the lift places on the table where the target stood (image centre of the first blob).
  std::vector<test::TestGaussian> gs(1);
  gs[0].pos = {0.0f, 0.0f, -16.0f / cam.fy * 5.0f};
  ASSERT_EQ(cam.pixel_of(cam.to_camera(gs[0].pos)), 48 * n + 32);
  const GaussianModel model = test::make_model(gs);
  EXPECT_FLOAT_EQ(glossy_mask_emit_weights(model, {view})[0], 1.0f);  // the target's vote: it emits

  TrainView no_mask;  // left alone
  no_mask.name = "r_001";
  no_mask.camera = cam;
  std::vector<TrainView> views{view, no_mask};
  std::vector<InpaintMaskView> holes(2);
  holes[0].covered = hole.covered;
  holes[1].covered = hole.covered;
  const std::size_t filled = fill_removed_glossy_masks(views, holes);  // radius 1 at 64 px
  EXPECT_EQ(filled, count_set(dilate_mask(hole.covered, 1)));
  EXPECT_TRUE(views[1].glossy_mask.empty());
  const std::vector<float>& m = views[0].glossy_mask;
  for (int y = 40; y < 56; ++y)
    for (int x = 24; x < 40; ++x) EXPECT_GT(m[std::size_t(y) * n + x], 0.99f) << x << "," << y;
  const float low = m[37 * n + 50], high = m[27 * n + 50];  // the straddling blob blends table and background
  EXPECT_GT(low, high + 0.2f);
  EXPECT_GT(high, 0.0f);
  EXPECT_LT(low, 1.0f);
  const Mask grown = dilate_mask(hole.covered, 1);
  for (std::size_t p = 0; p < m.size(); ++p)
    if (!grown.data[p]) ASSERT_EQ(m[p], before[p]) << "pixel " << p << " outside the target changed";
  EXPECT_LT(glossy_mask_emit_weights(model, {views[0]})[0], 0.01f);  // the table's vote: no ghost

  // Written and read back as a glossy_mask_dir (8-bit PNG).
  const auto dir = test::scratch_dir("removed_glossy_masks");
  std::vector<TrainView> masked{views[0]};
  save_glossy_mask_folder(dir, masked);
  masked[0].glossy_mask.clear();
  load_glossy_mask_folder(dir, masked);
  ASSERT_EQ(masked[0].glossy_mask.size(), m.size());
  for (std::size_t p = 0; p < m.size(); ++p) ASSERT_NEAR(masked[0].glossy_mask[p], m[p], 0.5f / 255.0f + 1e-6f);
  test::expect_error([&] { save_glossy_mask_folder(dir, views); }, "r_001 has no glossy mask");

  // A coverage of another size names the view.
  std::vector<InpaintMaskView> small(1);
  small[0].covered = Mask(n / 2, n / 2);
  std::vector<TrainView> one{view};
  test::expect_error([&] { fill_removed_glossy_masks(one, small); }, "training view r_000");
}

// The setting is read by name, written back by the same name, and anything else is refused with the choices.
TEST(EmitWeights, ConfigAcceptsOnlyItsEmitSources) {
  TrainConfig c;
  apply_config_overrides({"intrinsic_emit=max"}, c, "set");
  EXPECT_EQ(c.intrinsic.emit, EmitSource::Max);
  nlohmann::json j;
  to_json(j, c);
  EXPECT_EQ(j.at("intrinsic_emit"), "max");
  test::expect_error([&] { apply_config_overrides({"intrinsic_emit=glossy"}, c, "set"); },
                     "'intrinsic_emit' must be region, mask or max, got \"glossy\"");
  test::expect_error([&] { apply_config_overrides({"intrinsic_emit=1"}, c, "set"); }, "must be region, mask or max");
  EXPECT_EQ(c.intrinsic.emit, EmitSource::Max);
}

}  // namespace
}  // namespace goris
