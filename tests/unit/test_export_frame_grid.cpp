// The contact sheet of `goris export --renders` (export/frames/frame_grid.h): layout and frame placement.
#include <vector>

#include "core/util/error.h"
#include "export/frames/frame_grid.h"
#include "tests/support/test_support.h"

using namespace goris;

namespace {

Image solid(int w, int h, float r, float g, float b) {
  std::vector<float> px(size_t(w) * h * 3);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    px[i * 3] = r;
    px[i * 3 + 1] = g;
    px[i * 3 + 2] = b;
  }
  Image img(w, h, 3);
  img.pixels.upload(px.data(), px.size());
  return img;
}

}  // namespace

TEST(ExportFrameGrid, Layout) {
  const FrameGrid a = frame_grid_layout(4, 64, 48);
  EXPECT_EQ(a.columns, 2);
  EXPECT_EQ(a.rows, 2);
  EXPECT_EQ(a.cell_width, 64);  // never enlarged
  EXPECT_EQ(a.cell_height, 48);
  const FrameGrid b = frame_grid_layout(10, 800, 400, 1000);
  EXPECT_EQ(b.columns, 4);
  EXPECT_EQ(b.rows, 3);
  EXPECT_LE(b.columns * (b.cell_width + FrameGrid::kGap) + FrameGrid::kGap, 1000);
  EXPECT_NEAR(b.cell_height, b.cell_width / 2.0, 1.0);  // aspect kept
  EXPECT_EQ(frame_grid_layout(1, 5, 5).columns, 1);
  EXPECT_THROW(frame_grid_layout(0, 5, 5), Error);
  EXPECT_THROW(frame_grid_layout(3, 0, 5), Error);
}

TEST(ExportFrameGrid, FramesLandInOrderRowByRow) {
  const FrameGrid g = frame_grid_layout(3, 8, 6);
  std::vector<Image> frames;
  frames.push_back(solid(8, 6, 1, 0, 0));
  frames.push_back(solid(8, 6, 0, 1, 0));
  frames.push_back(solid(8, 6, 0, 0, 1));
  const Image sheet = compose_frame_grid(g, frames);
  const int gap = FrameGrid::kGap;
  ASSERT_EQ(sheet.width, 2 * (8 + gap) + gap);
  ASSERT_EQ(sheet.height, 2 * (6 + gap) + gap);
  const std::vector<float> px = sheet.pixels.to_host();
  auto at = [&](int x, int y, int c) { return px[(size_t(y) * sheet.width + x) * 3 + c]; };
  EXPECT_EQ(at(gap + 3, gap + 2, 0), 1.0f);                 // frame 0: top left, red
  EXPECT_EQ(at(2 * gap + 8 + 3, gap + 2, 1), 1.0f);         // frame 1: top right, green
  EXPECT_EQ(at(gap + 3, 2 * gap + 6 + 2, 2), 1.0f);         // frame 2: second row, blue
  EXPECT_NEAR(at(0, 0, 0), 0.15f, 1e-6f);                   // gaps are dark grey
  EXPECT_NEAR(at(2 * gap + 8 + 3, 2 * gap + 6 + 2, 1), 0.15f, 1e-6f);  // the empty cell too
  EXPECT_THROW(compose_frame_grid(g, {}), Error);
  EXPECT_THROW(compose_frame_grid(g, std::vector<Image>(5)), Error);
}
