// The glossy surface's own detail round the hole (removal/lift/surface_detail.h): zero on a plain surface
// whatever lies inside the hole or beyond the surface's edge, the stripes' amplitude on a striped one.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/util/error.h"
#include "removal/lift/surface_detail.h"

namespace goris {
namespace {

constexpr int kW = 64, kH = 48;

Image colour(const std::function<float(int x, int y, int c)>& f) {
  Image im(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) im.pixels[(std::size_t(y) * kW + x) * 3 + std::size_t(c)] = f(x, y, c);
  return im;
}

// The surface: the lower part of the image (y >= 16); the hole: a 12 x 12 square on it.
std::vector<float> surface() {
  std::vector<float> g(std::size_t(kW) * kH, 0.0f);
  for (int y = 16; y < kH; ++y)
    for (int x = 0; x < kW; ++x) g[std::size_t(y) * kW + x] = 1.0f;
  return g;
}
bool in_hole(int x, int y) { return x >= 26 && x < 38 && y >= 26 && y < 38; }
Mask hole() {
  Mask m(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) m.set(x, y, in_hole(x, y));
  return m;
}

TEST(SurfaceDetail, APlainSurfaceHasNoneWhateverTheHoleAndTheBackgroundHold) {
  // A bright target in the hole and a dark wall above the surface's edge: neither is the surface's detail.
  const Image im = colour([](int x, int y, int c) {
    if (in_hole(x, y)) return 1.0f;
    return y < 16 ? 0.05f : 0.3f + 0.1f * float(c);
  });
  const auto d = surface_detail_rms(im, surface(), hole());
  ASSERT_TRUE(d.has_value());
  EXPECT_LT(*d, 1e-6);
}

TEST(SurfaceDetail, AStripedSurfaceMeasuresItsStripes) {
  // Stripes of +-0.1 with a period of 2 px: a sigma-2 blur flattens them, so the residual's RMS is about 0.1.
  const Image striped = colour([](int x, int y, int c) {
    (void)c;
    if (y < 16 || in_hole(x, y)) return 0.9f;
    return 0.5f + ((x % 2) ? 0.1f : -0.1f);
  });
  const auto d = surface_detail_rms(striped, surface(), hole());
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, 0.1, 0.01);
  EXPECT_GT(*d, SurfaceDetailSettings{}.textured_above);
  // A smooth ramp across the surface is no texture.
  const Image ramp = colour([](int x, int y, int c) { return (void)y, (void)c, 0.2f + 0.5f * float(x) / kW; });
  EXPECT_LT(*surface_detail_rms(ramp, surface(), hole()), 0.1 * SurfaceDetailSettings{}.textured_above);
}

TEST(SurfaceDetail, TooLittleSurfaceGivesNoMeasureAndTheMedianSkipsIt) {
  std::vector<float> sliver(std::size_t(kW) * kH, 0.0f);
  for (int x = 0; x < kW; ++x) sliver[std::size_t(40) * kW + x] = 1.0f;  // one row: no interior at all
  const Image im = colour([](int, int, int) { return 0.5f; });
  EXPECT_FALSE(surface_detail_rms(im, sliver, hole()).has_value());
  EXPECT_FALSE(median_surface_detail({std::nullopt, std::nullopt}).has_value());
  EXPECT_DOUBLE_EQ(*median_surface_detail({0.01, std::nullopt, 0.05, 0.03}), 0.03);
}

TEST(SurfaceDetail, MismatchedSizesAreAnError) {
  const Image im = colour([](int, int, int) { return 0.5f; });
  EXPECT_THROW(surface_detail_rms(im, std::vector<float>(10, 1.0f), hole()), Error);
  EXPECT_THROW(surface_detail_rms(im, surface(), Mask(kW / 2, kH)), Error);
}

}  // namespace
}  // namespace goris
