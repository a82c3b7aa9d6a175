// The two-click selection's every-view vote and its support plane: the silhouette of a selection covers
// what unselected Gaussians hide of it (a selection of the object's near side covers the whole object from
// the far side), glossy pixels are never the target, and Gaussians beyond the surface the target stands on
// (its reflection in a mirror world) are left out, on the table-and-box scene.
#include <gtest/gtest.h>

#include <vector>

#include "core/scene/selection_points.h"
#include "core/util/error.h"
#include "removal/selection/selection_click_flow.h"
#include "removal/selection/selection_click_region.h"
#include "removal/selection/selection_masks.h"
#include "removal/selection/selection_view_masks.h"
#include "tests/support/table_box_scene.h"

namespace goris {
namespace {

// The box's Gaussians on the side y < 0 only: from a camera on the +y side they are behind the other half.
SelectionMask near_half(const test::SceneBuilder& scene) {
  SelectionMask m(scene.target.size(), 0);
  for (std::size_t k = 0; k < m.size(); ++k) m[k] = scene.target[k] && scene.pos[3 * k + 1] < 0.0f;
  return m;
}

TEST(ClickFlowVote, SilhouetteCoversWhatUnselectedGaussiansHide) {
  const test::SceneBuilder scene = test::table_and_box(0.0f, 0.4f);
  const GaussianModel model = scene.model();
  const Camera far_side = test::table_cameras()[3];  // azimuth 90 degrees: the +y side
  const SelectionMask half = near_half(scene);
  const std::size_t box = count_set(selection_view_mask(model, scene.target, far_side));
  const std::size_t hidden = count_set(selection_view_mask(model, half, far_side));
  const std::size_t silhouette = count_set(selection_silhouette_mask(model, half, far_side));
  ASSERT_GT(box, 100u);
  // Through the full render the near half shows only where it rises above the far half's top.
  EXPECT_LT(double(hidden), 0.35 * double(box));
  // Alone it covers most of the box's outline (its own far face lies half a box further back, so a little
  // of the top and the sides stays out).
  EXPECT_GT(double(silhouette), 0.7 * double(box));
  EXPECT_GT(silhouette, 2 * hidden);
  EXPECT_THROW(selection_silhouette_mask(model, SelectionMask(3, 1), far_side), Error);
}

TEST(ClickFlowVote, EveryViewsVoteCompletesAHalfSelectionAndNeverTakesGlossyPixels) {
  const test::SceneBuilder scene = test::table_and_box(0.0f, 0.4f);
  const GaussianModel model = scene.model();
  std::vector<View> views;
  for (const Camera& c : test::table_cameras()) views.push_back({"v" + std::to_string(views.size()), c});
  const SelectionMask half = near_half(scene);
  std::size_t target = 0, half_count = 0;
  for (std::size_t k = 0; k < half.size(); ++k) target += scene.target[k], half_count += half[k];

  // Per selection: the box's Gaussians on the far side (y > 0), the box's in all, the table's.
  auto score = [&](const SelectionMask& sel, std::size_t& far, std::size_t& box, std::size_t& table) {
    far = box = table = 0;
    for (std::size_t k = 0; k < sel.size(); ++k)
      if (sel[k]) {
        ++(scene.target[k] ? box : table);
        far += scene.target[k] && scene.pos[3 * k + 1] > 0.0f;
      }
  };
  std::size_t far = 0, box = 0, table = 0;
  score(revote_with_view_masks(model, half, views), far, box, table);
  // The far half's surface joins (the vote takes the Gaussians each view shows: the box's inside is for the
  // closing); a few table Gaussians at the box's foot come too, a small share of it.
  EXPECT_GT(far, 40u);
  EXPECT_LT(double(table), 0.1 * double(box));
  // Masks from the coverage in the full render (the far half hides the selection there) take far fewer.
  std::vector<MaskedView> covered;
  for (const View& v : views) covered.push_back({v.name, v.camera, mask_to_image(selection_view_mask(model, half, v.camera))});
  std::size_t far_covered = 0, box_covered = 0, table_covered = 0;
  score(labels_from_masks(model, covered).selected, far_covered, box_covered, table_covered);
  EXPECT_LT(2 * far_covered, far);
  (void)target;
  (void)half_count;

  // Glossy masks that mark the whole image: no pixel is the target, and the vote keeps nothing.
  std::vector<std::vector<float>> all_glossy;
  std::vector<const std::vector<float>*> glossy;
  for (const View& v : views) all_glossy.emplace_back(std::size_t(v.camera.width * v.camera.height), 1.0f);
  for (const auto& g : all_glossy) glossy.push_back(&g);
  score(revote_with_view_masks(model, half, views, {}, glossy), far, box, table);
  EXPECT_EQ(box + table, 0u);
  // A glossy mask of another size than its view is an error, not a silent skip.
  all_glossy[2].resize(10);
  EXPECT_THROW(revote_with_view_masks(model, half, views, {}, glossy), Error);
}

TEST(ClickFlowSupport, GaussiansBeyondThePlaneByMoreThanItsToleranceAreDropped) {
  SelectionPoints pts;
  pts.position = {{0, 0, 0.3f}, {0, 0, -0.01f}, {0, 0, -0.2f}, {0, 0, -0.03f}, {1, 1, -0.5f}};
  MirrorPlane plane;
  plane.found = true;
  plane.normal = {0, 0, 1};
  plane.offset = 0.0;
  plane.tolerance = 0.02;
  SelectionMask sel = {1, 1, 1, 1, 0};
  EXPECT_EQ(drop_beyond_plane(pts, plane, sel), 2u);
  EXPECT_EQ(sel, (SelectionMask{1, 1, 0, 0, 0}));
  // No plane: nothing dropped.
  SelectionMask all = {1, 1, 1, 1, 1};
  EXPECT_EQ(drop_beyond_plane(pts, MirrorPlane{}, all), 0u);
  EXPECT_EQ(count_selected(all), 5u);
}

}  // namespace
}  // namespace goris
