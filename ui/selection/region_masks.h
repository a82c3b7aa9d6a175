#pragma once
// The selection tools' regions as masks over a model's Gaussians, computed with the library's selection
// rules (removal/selection/selection.h): a rectangle, lasso or brush stroke in a view's pixels (through the
// depth or through everything), a sphere or an oriented box, a colour range. Nothing here touches threads
// or the GUI; the editor runs these on its selection worker.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/scene/selection_points.h"
#include "removal/selection/selection_ops.h"
#include "removal/selection/selection_screen.h"
#include "render/raster/raster_types.h"

namespace goris {
class GaussianModel;
}

namespace goris::ui {

// A shape drawn on one view: points in the camera's continuous pixel coordinates.
struct ScreenRegion {
  enum class Kind { Rect, Polygon, Brush };
  Kind kind = Kind::Rect;
  Camera camera;
  std::vector<glm::vec2> points;  // rect: two opposite corners; polygon: >= 3 vertices; brush: the stroke
  float radius = 10.0f;           // brush: the disc's radius in pixels
  Through through = Through::Visible;
};
const char* screen_region_name(ScreenRegion::Kind kind);  // "rect", "polygon", "brush"

// The Gaussians whose centre the region covers. With Through::Visible, `model` decides what the view shows
// (pass a model whose hidden Gaussians are transparent, so they hide nothing). Throws goris::Error for a
// polygon of fewer than three vertices or an empty stroke.
SelectionMask screen_region_mask(const GaussianModel& model, const SelectionPoints& pts, const ScreenRegion& region,
                                 const RasterSettings& raster);

// A placed volume: a sphere (centre, radius) or a box (centre, half extents, Euler angles in degrees about
// x, then y, then z, as `goris select --box`).
struct VolumeRegion {
  enum class Kind { Sphere, Box };
  Kind kind = Kind::Sphere;
  glm::vec3 centre{0.0f};
  float radius = 0.5f;
  glm::vec3 half_extent{0.5f};
  glm::vec3 rotation_degrees{0.0f};
};
const char* volume_region_name(VolumeRegion::Kind kind);  // "sphere", "box"
SelectionBox volume_box(const VolumeRegion& v);
SelectionMask volume_mask(const SelectionPoints& pts, const VolumeRegion& v);

// For the selection panel's list, e.g. "rect (10, 12)-(40, 50), visible", "sphere at (0, 0, 0.1) r 0.3".
std::string describe(const ScreenRegion& r);
std::string describe(const VolumeRegion& v);

}  // namespace goris::ui
