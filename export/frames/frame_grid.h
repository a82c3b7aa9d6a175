#pragma once
// A contact sheet of rendered frames: one PNG with every frame of an export side by side, in order, row by
// row, so a person sees a whole orbit or test set at a glance.
#include <vector>

#include "core/io/image.h"

namespace goris {

struct FrameGrid {
  int columns = 0, rows = 0;
  int cell_width = 0, cell_height = 0;  // each frame's size on the sheet
  static constexpr int kGap = 2;        // pixels between cells and around the sheet
};

// The layout for `count` frames of width x height: ceil(sqrt(count)) columns, cells shrunk (keeping the
// aspect) so the sheet is at most max_width pixels wide, never enlarged. Throws goris::Error for no frames.
FrameGrid frame_grid_layout(int count, int width, int height, int max_width = 2048);

// The sheet (RGB, on the CPU, dark grey gaps): frames[i] (RGB on any device) lands in cell i after being
// resized to the cell (area averaging). Throws goris::Error when the frame count or sizes do not fit.
Image compose_frame_grid(const FrameGrid& grid, const std::vector<Image>& frames);

}  // namespace goris
