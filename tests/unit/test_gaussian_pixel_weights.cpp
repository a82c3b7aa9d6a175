// Per-Gaussian rendered weight inside and outside a mask: for a lone Gaussian it is its alpha image, summed
// over each side of the mask.
#include <gtest/gtest.h>

#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/selection/gaussian_pixel_weights.h"
#include "removal/selection/select_view.h"
#include "render/raster/rasterizer.h"
#include "tests/support/table_box_scene.h"

namespace goris {
namespace {

TEST(GaussianPixelWeights, ALoneGaussiansWeightsSumToItsAlphaImage) {
  test::SceneBuilder s;
  s.add({0.05f, -0.03f, 0.3f}, {0.2f, 0.1f, 0.05f}, 0.5f, false);
  const GaussianModel model = s.model();
  const Camera cam = test::table_cameras()[0];
  Mask half(cam.width, cam.height);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width / 2; ++x) half.data[std::size_t(y) * cam.width + x] = 255;
  const PixelWeights w = gaussian_pixel_weights(model, {cam}, {half}, RasterSettings{});
  const std::vector<float> alpha = rasterize(plain_gaussian_view(model), cam, {}, Device::CPU).gbuffer.alpha.to_host();
  double in = 0, out = 0;
  for (std::size_t p = 0; p < alpha.size(); ++p) (half.data[p] ? in : out) += alpha[p];
  EXPECT_GT(in, 10.0);
  EXPECT_GT(out, 10.0);
  EXPECT_NEAR(w.inside[0], in, 1e-3 * in);
  EXPECT_NEAR(w.outside[0], out, 1e-3 * out);
  EXPECT_THROW(gaussian_pixel_weights(model, {cam}, {}, RasterSettings{}), Error);
  EXPECT_THROW(gaussian_pixel_weights(model, {cam}, {Mask(3, 3)}, RasterSettings{}), Error);
}

}  // namespace
}  // namespace goris
