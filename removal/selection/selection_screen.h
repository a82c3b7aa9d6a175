#pragma once
// Selecting in screen space: the Gaussians whose centre projects inside a polygon (a lasso, a rectangle,
// a brush stroke's disc) of one camera. "Through everything" takes every such centre in front of the
// camera; "through the depth" only those the view shows, which needs a render
// (removal/selection/selection_region.h).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/scene/selection_points.h"

namespace goris {

// Vertices in continuous pixel coordinates (pixel i spans [i, i + 1)), in order; closed implicitly. At least
// three vertices; self-intersecting outlines follow the even-odd rule.
using ScreenPolygon = std::vector<glm::vec2>;

enum class Through { Visible, All };
const char* through_name(Through t);                 // "visible", "all"
Through through_from_name(const std::string& name);  // the same names; anything else is a goris::Error

// The axis-aligned rectangle with corners a and b (any two opposite corners).
ScreenPolygon rect_polygon(const glm::vec2& a, const glm::vec2& b);
// A disc as a 32-gon (the brush).
ScreenPolygon disc_polygon(const glm::vec2& centre, float radius);
// Parses "a,b,c,..." (finite numbers); `what` names the argument in errors.
std::vector<float> parse_number_list(const std::string& text, const std::string& what);
// Parses "x,y,x,y,..." (at least three points); `what` names the argument in errors.
ScreenPolygon parse_polygon(const std::string& text, const std::string& what);

bool inside_polygon(const ScreenPolygon& polygon, const glm::vec2& p);

// Per Gaussian, the pixel (y * width + x) its centre projects to, or -1 when it lies behind near_plane or
// outside the image.
std::vector<std::int32_t> centre_pixels(const std::vector<glm::vec3>& positions, const Camera& camera,
                                        float near_plane);

// Centres that project inside `polygon`; with `visible` (per Gaussian, from the render) only where it is 1.
SelectionMask select_in_polygon(const std::vector<glm::vec3>& positions, const Camera& camera,
                                const ScreenPolygon& polygon, float near_plane,
                                const std::vector<std::uint8_t>* visible = nullptr);

}  // namespace goris
