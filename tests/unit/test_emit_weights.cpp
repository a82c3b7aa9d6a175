// Emit weights from the glossy masks (core/train/emit_weights.h, intrinsic_emit = mask): a Gaussian that
// projects onto the glossy mask does not emit, one beside it does, one no view sees keeps 1, and views
// without a mask do not vote.
#include <gtest/gtest.h>

#include <vector>

#include "core/train/emit_weights.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_selection_scene.h"

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

TEST(EmitWeights, ConfigAcceptsOnlyRegionOrMask) {
  TrainConfig c;
  c.intrinsic.emit = "mask";
  EXPECT_NO_THROW(c.validate("test"));
  c.intrinsic.emit = "glossy";
  test::expect_error([&] { c.validate("test"); }, "intrinsic_emit");
}

}  // namespace
}  // namespace goris
