#include "ui/document/panel_layout.h"

#include <algorithm>
#include <cmath>

namespace goris::ui {

StudioLayout compute_layout(const LayoutInput& in) {
  StudioLayout l;
  const float top = in.menu_height;
  const float bottom = std::max(top, in.height - in.status_height);
  l.status = {0, bottom, in.width, in.height - bottom};
  const float side = in.sidebar ? std::min(in.sidebar_width, in.width * 0.5f) : 0.0f;
  l.sidebar = {0, top, side, bottom - top};
  const Rect area{side, top, std::max(in.width - side, 0.0f), bottom - top};
  float grid_h = 0;
  if (in.grid_count > 0 && area.w > 0) {
    const float tile_w = area.w / float(in.grid_count);
    grid_h = std::min(tile_w * 0.75f, area.h * in.grid_max_fraction);
    for (int i = 0; i < in.grid_count; ++i)
      l.grid.push_back({area.x + tile_w * float(i), area.y + area.h - grid_h, tile_w, grid_h});
  }
  l.main = {area.x, area.y, area.w, area.h - grid_h};
  return l;
}

Rect fit_aspect(const Rect& r, float aspect) {
  if (!(aspect > 0) || r.w <= 0 || r.h <= 0) return {r.x, r.y, 0, 0};
  float w = r.w, h = r.w / aspect;
  if (h > r.h) {
    h = r.h;
    w = r.h * aspect;
  }
  return {r.x + 0.5f * (r.w - w), r.y + 0.5f * (r.h - h), w, h};
}

void capped_size(float w, float h, int max_side, int& out_w, int& out_h) {
  w = std::max(w, 1.0f);
  h = std::max(h, 1.0f);
  const float s = std::min(1.0f, float(std::max(max_side, 1)) / std::max(w, h));
  out_w = std::max(1, int(std::lround(w * s)));
  out_h = std::max(1, int(std::lround(h * s)));
}

}  // namespace goris::ui
