// The warm-up's mirror world (train/loop/mirror_world.h): a Gaussian seen only behind a glossy surface is
// found; one in front of it, one behind a rough surface, one seen behind the glossy surface in a single view
// and one that another view sees against the background are kept. Views without a glossy mask do not vote.
#include <gtest/gtest.h>

#include <vector>

#include "tests/support/test_support.h"
#include "tests/unit/test_selection_scene.h"
#include "train/loop/mirror_world.h"

namespace goris {
namespace {

constexpr int kSize = 64;

// Camera `eye` looking at the origin; its rendered surface lies `depth` in front of it everywhere except
// in the top rows, which show the background. The left half of the image is glossy.
struct FakeView {
  TrainView view;
  float depth;
};

FakeView fake_view(glm::vec3 eye, float depth) {
  FakeView f{{}, depth};
  f.view.camera = test::look_at(eye, {0.0f, 0.0f, 0.0f}, kSize, kSize, 60.0f);
  f.view.glossy_mask.assign(std::size_t(kSize) * kSize, 0.0f);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize / 2; ++x) f.view.glossy_mask[std::size_t(y) * kSize + std::size_t(x)] = 1.0f;
  return f;
}

TEST(MirrorWorld, OnlyGaussiansSeenBehindGlossySurfacesAlone) {
  // Cameras at y = -5 (and slightly beside it) looking along +y: world x is image right, z is image up.
  // The rendered surface is the plane 4 units in front of each camera (world y ~ -1).
  std::vector<FakeView> views = {fake_view({0.0f, -5.0f, 0.0f}, 4.0f), fake_view({0.3f, -5.0f, 0.0f}, 4.0f),
                                 fake_view({-0.3f, -5.0f, 0.0f}, 4.0f)};
  std::vector<test::TestGaussian> gs(5);
  gs[0].pos = {-1.0f, 1.0f, 0.0f};   // behind the glossy half in every view: mirror world
  gs[1].pos = {-1.0f, -2.0f, 0.0f};  // in front of the glossy half: seen
  gs[2].pos = {1.0f, 1.0f, 0.0f};    // behind the rough half: occluded, kept
  gs[3].pos = {-1.0f, 1.0f, 0.0f};   // like 0, but the third view sees it against the background
  gs[4].pos = {-1.0f, 1.0f, -0.5f};  // like 0, but only the first view has a glossy mask there
  const GaussianModel model = test::make_model(gs);
  std::vector<TrainView> tv;
  for (const FakeView& f : views) tv.push_back(f.view);
  // Gaussian 4 projects below the centre row; only view 0 keeps its mask there.
  for (size_t v = 1; v < tv.size(); ++v)
    for (int y = kSize / 2 + 2; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) tv[v].glossy_mask[std::size_t(y) * kSize + std::size_t(x)] = 0.0f;
  int call = 0;
  const DepthAlphaRender render = [&](const Camera& c, std::vector<float>& depth, std::vector<float>& alpha) {
    const size_t n = size_t(c.width) * size_t(c.height);
    depth.assign(n, views[size_t(call)].depth);
    alpha.assign(n, 1.0f);
    if (call == 2) {  // the third view: Gaussian 3's pixel shows the background
      const glm::vec2 uv = c.project_camera(c.to_camera(gs[3].pos));
      alpha[size_t(uv.y) * size_t(c.width) + size_t(uv.x)] = 0.0f;
    }
    ++call;
  };
  // Gaussians 0 and 3 share a position; tell them apart by index only after the first check.
  std::vector<std::uint8_t> mirror = find_mirror_world(model, tv, render, 0.05f, 2);
  ASSERT_EQ(mirror.size(), 5u);
  EXPECT_EQ(call, 3);
  EXPECT_EQ(mirror[0], 0) << "Gaussian 0 shares Gaussian 3's pixel, which view 2 sees against the background";
  EXPECT_EQ(mirror[1], 0);
  EXPECT_EQ(mirror[2], 0);
  EXPECT_EQ(mirror[3], 0);
  EXPECT_EQ(mirror[4], 0) << "behind a glossy pixel in one view only";
  // Without the background pixel, 0 and 3 are mirror world; a view without a mask does not vote.
  call = 0;
  tv.push_back(TrainView{});
  tv.back().camera = tv[0].camera;
  const DepthAlphaRender plain = [&](const Camera& c, std::vector<float>& depth, std::vector<float>& alpha) {
    depth.assign(size_t(c.width) * size_t(c.height), views[size_t(std::min(call, 2))].depth);
    alpha.assign(depth.size(), 1.0f);
    ++call;
  };
  mirror = find_mirror_world(model, tv, plain, 0.05f, 2);
  EXPECT_EQ(call, 3) << "the view without a glossy mask is not rendered";
  EXPECT_EQ(mirror[0], 1);
  EXPECT_EQ(mirror[3], 1);
  EXPECT_EQ(mirror[1], 0);
  EXPECT_EQ(mirror[2], 0);
  EXPECT_EQ(mirror[4], 0);
  // A tolerance beyond the Gaussian's depth keeps it "at the surface".
  call = 0;
  mirror = find_mirror_world(model, tv, plain, 1.0f, 2);
  EXPECT_EQ(mirror[0], 0);
  call = 0;
  EXPECT_THROW(find_mirror_world(model, tv, plain, -1.0f, 2), Error);
}

}  // namespace
}  // namespace goris
