#pragma once
// Where everything goes in the window (Dear ImGui 1.86 has no docking): a menu bar on top, a status bar at
// the bottom, an optional sidebar of panels on the left, and the viewports in the rest: the main viewport
// above a row of grid tiles. Pure arithmetic, so it is unit-tested.
#include <vector>

namespace goris::ui {

struct Rect {
  float x = 0, y = 0, w = 0, h = 0;  // window pixels, origin top-left
  bool contains(float px, float py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

struct LayoutInput {
  float width = 0, height = 0;  // the window
  float menu_height = 0, status_height = 0;
  bool sidebar = true;
  float sidebar_width = 340;
  int grid_count = 4;               // 0 = no grid
  float grid_max_fraction = 0.34f;  // the grid row takes at most this share of the height
};

struct StudioLayout {
  Rect sidebar;            // w = 0 when hidden
  Rect main;               // the main viewport
  std::vector<Rect> grid;  // grid_count tiles, left to right
  Rect status;
};

StudioLayout compute_layout(const LayoutInput& in);

// The largest rectangle of `aspect` (width / height) centred in `r` (letterboxing).
Rect fit_aspect(const Rect& r, float aspect);

// The size of a render for a box of `w` x `h` pixels, keeping its aspect and at most `max_side` pixels on
// the longest side (and at least 1 x 1).
void capped_size(float w, float h, int max_side, int& out_w, int& out_h);

}  // namespace goris::ui
