#include "ui/selection/region_masks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/util/error.h"
#include "removal/selection/selection_region.h"

namespace goris::ui {

const char* screen_region_name(ScreenRegion::Kind kind) {
  switch (kind) {
    case ScreenRegion::Kind::Rect:
      return "rect";
    case ScreenRegion::Kind::Polygon:
      return "polygon";
    case ScreenRegion::Kind::Brush:
      return "brush";
  }
  return "rect";
}

const char* volume_region_name(VolumeRegion::Kind kind) { return kind == VolumeRegion::Kind::Box ? "box" : "sphere"; }

namespace {

// The stroke's points, resampled so that consecutive discs overlap (at most half a radius apart).
std::vector<glm::vec2> brush_centres(const std::vector<glm::vec2>& stroke, float radius) {
  std::vector<glm::vec2> out;
  const float step = std::max(0.5f * radius, 0.5f);
  for (std::size_t k = 0; k < stroke.size(); ++k) {
    if (k == 0) {
      out.push_back(stroke[0]);
      continue;
    }
    const glm::vec2 a = stroke[k - 1], b = stroke[k];
    const int n = int(std::ceil(glm::length(b - a) / step));
    for (int i = 1; i <= n; ++i) out.push_back(a + (b - a) * (float(i) / float(n)));
  }
  return out;
}

}  // namespace

SelectionMask screen_region_mask(const GaussianModel& model, const SelectionPoints& pts, const ScreenRegion& r,
                                 const RasterSettings& raster) {
  const char* what = screen_region_name(r.kind);
  switch (r.kind) {
    case ScreenRegion::Kind::Rect:
      if (r.points.size() != 2) throw Error(what, "needs two corners");
      return select_in_view_region(model, pts, r.camera, rect_polygon(r.points[0], r.points[1]), r.through, raster);
    case ScreenRegion::Kind::Polygon:
      if (r.points.size() < 3) throw Error(what, "needs at least three points");
      return select_in_view_region(model, pts, r.camera, r.points, r.through, raster);
    case ScreenRegion::Kind::Brush:
      break;
  }
  if (r.points.empty()) throw Error(what, "the stroke has no points");
  if (!(r.radius > 0.0f)) throw Error(what, "the radius must be positive");
  // Which centres the view shows is found once for the whole stroke; each disc then only tests them.
  std::vector<std::uint8_t> visible;
  if (r.through == Through::Visible) {
    const std::vector<std::int32_t> px = visible_centre_pixels(model, pts.position, pts.scale, r.camera, raster);
    visible.resize(px.size());
    for (std::size_t i = 0; i < px.size(); ++i) visible[i] = px[i] >= 0;
  }
  SelectionMask result(pts.size(), 0);
  for (const glm::vec2& c : brush_centres(r.points, r.radius)) {
    const SelectionMask disc = select_in_polygon(pts.position, r.camera, disc_polygon(c, r.radius), raster.near_plane,
                                                 visible.empty() ? nullptr : &visible);
    result = combine_selections(result, disc, Combine::Union);
  }
  return result;
}

SelectionBox volume_box(const VolumeRegion& v) {
  SelectionBox b;
  b.centre = v.centre;
  b.half_extent = v.half_extent;
  b.rotation = rotation_from_euler_degrees(v.rotation_degrees);
  return b;
}

SelectionMask volume_mask(const SelectionPoints& pts, const VolumeRegion& v) {
  if (v.kind == VolumeRegion::Kind::Sphere) {
    if (!(v.radius >= 0.0f)) throw Error("sphere", "the radius must not be negative");
    return select_sphere(pts, v.centre, v.radius);
  }
  if (!(v.half_extent.x >= 0.0f && v.half_extent.y >= 0.0f && v.half_extent.z >= 0.0f))
    throw Error("box", "half extents must not be negative");
  return select_box(pts, volume_box(v));
}

std::string describe(const ScreenRegion& r) {
  char b[160];
  const char* through = through_name(r.through);
  if (r.kind == ScreenRegion::Kind::Rect && r.points.size() == 2)
    std::snprintf(b, sizeof b, "rect (%.0f, %.0f)-(%.0f, %.0f), %s", double(r.points[0].x), double(r.points[0].y),
                  double(r.points[1].x), double(r.points[1].y), through);
  else if (r.kind == ScreenRegion::Kind::Brush)
    std::snprintf(b, sizeof b, "brush stroke of %zu points, radius %.0f, %s", r.points.size(), double(r.radius),
                  through);
  else
    std::snprintf(b, sizeof b, "%s of %zu points, %s", screen_region_name(r.kind), r.points.size(), through);
  return b;
}

std::string describe(const VolumeRegion& v) {
  char b[200];
  if (v.kind == VolumeRegion::Kind::Sphere)
    std::snprintf(b, sizeof b, "sphere at (%.3g, %.3g, %.3g), radius %.3g", double(v.centre.x), double(v.centre.y),
                  double(v.centre.z), double(v.radius));
  else
    std::snprintf(b, sizeof b, "box at (%.3g, %.3g, %.3g), half (%.3g, %.3g, %.3g)", double(v.centre.x),
                  double(v.centre.y), double(v.centre.z), double(v.half_extent.x), double(v.half_extent.y),
                  double(v.half_extent.z));
  return b;
}

}  // namespace goris::ui
