#include "export/frames/frame_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/error.h"

namespace goris {

FrameGrid frame_grid_layout(int count, int width, int height, int max_width) {
  if (count < 1) throw Error("contact sheet", "no frames");
  if (width < 1 || height < 1) throw Error("contact sheet", "frames must have a positive size");
  FrameGrid g;
  g.columns = int(std::ceil(std::sqrt(double(count))));
  g.rows = (count + g.columns - 1) / g.columns;
  const int room = std::max(g.columns, max_width - FrameGrid::kGap * (g.columns + 1));
  g.cell_width = std::min(width, room / g.columns);
  g.cell_height = std::max(1, int(std::lround(double(height) * double(g.cell_width) / double(width))));
  return g;
}

Image compose_frame_grid(const FrameGrid& g, const std::vector<Image>& frames) {
  if (frames.empty() || int(frames.size()) > g.columns * g.rows)
    throw Error("contact sheet", std::to_string(frames.size()) + " frames do not fit a " + std::to_string(g.columns) +
                                     " x " + std::to_string(g.rows) + " grid");
  const int gap = FrameGrid::kGap;
  const int W = g.columns * (g.cell_width + gap) + gap, H = g.rows * (g.cell_height + gap) + gap;
  std::vector<float> sheet(size_t(W) * size_t(H) * 3, 0.15f);
  for (size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].channels != 3) throw Error("contact sheet", "frame " + std::to_string(i) + " is not RGB");
    const std::vector<float> cell = resize_image(frames[i], g.cell_width, g.cell_height).pixels.to_host();
    const int x0 = gap + int(i % size_t(g.columns)) * (g.cell_width + gap);
    const int y0 = gap + int(i / size_t(g.columns)) * (g.cell_height + gap);
    for (int y = 0; y < g.cell_height; ++y)
      std::copy_n(cell.begin() + std::ptrdiff_t(size_t(y) * g.cell_width * 3), size_t(g.cell_width) * 3,
                  sheet.begin() + std::ptrdiff_t((size_t(y0 + y) * W + size_t(x0)) * 3));
  }
  Image out(W, H, 3);
  out.pixels.upload(sheet.data(), sheet.size());
  return out;
}

}  // namespace goris
