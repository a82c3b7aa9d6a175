// The lift's depth never in front of the glossy plane: pixels of the mask whose depth lies in front of the
// plane (or who have none) get the camera z of where their ray meets it (so that they back-project onto
// it); a depth beyond the plane, the pixels outside the mask and a plane behind the camera change nothing.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>

#include "core/util/error.h"
#include "removal/lift/plane_depth.h"
#include "removal/masks/inpaint_mask.h"
#include "tests/support/table_box_scene.h"

namespace goris {
namespace {

MirrorPlane level_plane(double height) {
  MirrorPlane p;
  p.found = true;
  p.normal = {0.0, 0.0, 1.0};
  p.offset = height;
  return p;
}

Image filled(const Camera& c, float value) {
  Image d(c.width, c.height, 1);
  for (std::size_t p = 0; p < d.pixel_count(); ++p) d.pixels[p] = value;
  return d;
}

TEST(DepthOntoPlane, MaskedPixelsBackProjectOntoThePlane) {
  // An oblique camera (45 degrees elevation, 3 away) over a floor at z = -0.07; the depth a fog gave: 2.0.
  const Camera c = test::table_cameras()[3];
  Image depth = filled(c, 2.0f);
  Mask where(c.width, c.height);
  for (int y = 20; y < 50; ++y)
    for (int x = 10; x < 40; ++x) where.set(x, y, true);
  const MirrorPlane plane = level_plane(-0.07);
  EXPECT_EQ(depth_onto_plane(depth, c, where, plane), 30u * 30u);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const float z = depth.pixels[std::size_t(y) * c.width + x];
      if (where(x, y))
        EXPECT_NEAR(back_project(c, x, y, z).z, -0.07f, 1e-4f) << x << "," << y;
      else
        EXPECT_EQ(z, 2.0f) << "outside the mask the depth stays";
    }
}

TEST(DepthOntoPlane, ADepthBeyondThePlaneStaysAndNoDepthGetsThePlanes) {
  const Camera c = test::table_cameras()[3];
  Image depth = filled(c, 10.0f);  // far beyond the floor in every pixel
  const Mask all(c.width, c.height, 255);
  const MirrorPlane plane = level_plane(-0.07);
  EXPECT_EQ(depth_onto_plane(depth, c, all, plane), 0u);
  for (std::size_t p = 0; p < depth.pixel_count(); ++p) EXPECT_EQ(depth.pixels[p], 10.0f);
  depth.pixels[32u * 64u + 32u] = 0.0f;  // no surface there
  EXPECT_EQ(depth_onto_plane(depth, c, all, plane), 1u);
  EXPECT_NEAR(back_project(c, 32, 32, depth.pixels[32u * 64u + 32u]).z, -0.07f, 1e-4f);
}

TEST(DepthOntoPlane, APlaneBehindTheCameraChangesNothing) {
  const Camera c = test::table_cameras()[3];  // above z = 0, looking down
  Image depth = filled(c, 2.0f);
  const Mask all(c.width, c.height, 255);
  // Above the camera: every ray looks down, away from it.
  EXPECT_EQ(depth_onto_plane(depth, c, all, level_plane(10.0)), 0u);
  for (std::size_t p = 0; p < depth.pixel_count(); ++p) EXPECT_EQ(depth.pixels[p], 2.0f);
  EXPECT_EQ(depth_onto_plane(depth, c, Mask(c.width, c.height), level_plane(-0.07)), 0u) << "an empty mask";
}

TEST(DepthOntoPlane, SizesThatDifferAreAnError) {
  const Camera c = test::table_cameras()[0];
  Image depth = filled(c, 1.0f);
  EXPECT_THROW(depth_onto_plane(depth, c, Mask(8, 8), level_plane(0.0)), Error);
  Image rgb(c.width, c.height, 3);
  EXPECT_THROW(depth_onto_plane(rgb, c, Mask(c.width, c.height), level_plane(0.0)), Error);
}

}  // namespace
}  // namespace goris
