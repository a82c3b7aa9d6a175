#pragma once
// Selection edits that need no rendering: combining two selections, inverting one, and choosing Gaussians
// by where their centre lies (a sphere, an oriented box) or by their colour. Each returns a SelectionMask
// over the Gaussians of `pts` (one byte per Gaussian, 1 = selected); mixing masks of different sizes is a
// goris::Error. Growing / shrinking by graph steps is in selection_grow.h, screen regions in
// selection_screen.h.
#include <string>

#include <glm/glm.hpp>

#include "core/scene/selection_points.h"

namespace goris {

enum class Combine { Union, Subtract, Intersect };
const char* combine_name(Combine op);                  // "union", "subtract", "intersect"
Combine combine_from_name(const std::string& name);     // the same names; anything else is a goris::Error

// a op b, per Gaussian: union a|b, subtract a&!b, intersect a&b.
SelectionMask combine_selections(const SelectionMask& a, const SelectionMask& b, Combine op);
SelectionMask invert_selection(const SelectionMask& mask);

// Centres within `radius` of `centre` (on the sphere counts as inside).
SelectionMask select_sphere(const SelectionPoints& pts, const glm::vec3& centre, float radius);

struct SelectionBox {
  glm::vec3 centre{0.0f};
  glm::vec3 half_extent{1.0f};
  glm::mat3 rotation{1.0f};  // the box's axes in world coordinates (columns); identity = axis-aligned
};
// Euler angles in degrees, applied about x, then y, then z (world axes): the box rotation they describe.
glm::mat3 rotation_from_euler_degrees(const glm::vec3& degrees);
// Centres inside the box (on a face counts as inside).
SelectionMask select_box(const SelectionPoints& pts, const SelectionBox& box);

// Gaussians whose SH DC colour (SelectionPoints::color) lies within `max_distance` (RGB Euclidean) of
// `reference`.
SelectionMask select_by_colour(const SelectionPoints& pts, const glm::vec3& reference, float max_distance);

}  // namespace goris
