#include "removal/selection/selection_ops.h"

#include <cmath>

#include "core/util/error.h"

namespace goris {

const char* combine_name(Combine op) {
  switch (op) {
    case Combine::Union: return "union";
    case Combine::Subtract: return "subtract";
    case Combine::Intersect: return "intersect";
  }
  return "union";
}

Combine combine_from_name(const std::string& name) {
  for (Combine op : {Combine::Union, Combine::Subtract, Combine::Intersect})
    if (name == combine_name(op)) return op;
  throw Error("selection", "unknown combination '" + name + "' (union, subtract or intersect)");
}

SelectionMask combine_selections(const SelectionMask& a, const SelectionMask& b, Combine op) {
  if (a.size() != b.size())
    throw Error("selection", "cannot combine selections of " + std::to_string(a.size()) + " and " +
                                 std::to_string(b.size()) + " Gaussians");
  SelectionMask out(a.size(), 0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool x = a[i] != 0, y = b[i] != 0;
    out[i] = op == Combine::Union ? (x || y) : op == Combine::Subtract ? (x && !y) : (x && y);
  }
  return out;
}

SelectionMask invert_selection(const SelectionMask& mask) {
  SelectionMask out(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) out[i] = mask[i] ? 0 : 1;
  return out;
}

SelectionMask select_sphere(const SelectionPoints& pts, const glm::vec3& centre, float radius) {
  if (!(radius >= 0.0f) || !std::isfinite(radius))
    throw Error("sphere", "radius must be a finite number >= 0, not " + std::to_string(radius));
  SelectionMask out(pts.size(), 0);
  const float r2 = radius * radius;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::vec3 d = pts.position[i] - centre;
    out[i] = glm::dot(d, d) <= r2;
  }
  return out;
}

glm::mat3 rotation_from_euler_degrees(const glm::vec3& deg) {
  const glm::vec3 r = glm::radians(deg);
  const float cx = std::cos(r.x), sx = std::sin(r.x), cy = std::cos(r.y), sy = std::sin(r.y), cz = std::cos(r.z),
              sz = std::sin(r.z);
  // glm is column-major: mat3(col0, col1, col2).
  const glm::mat3 rx(glm::vec3(1, 0, 0), glm::vec3(0, cx, sx), glm::vec3(0, -sx, cx));
  const glm::mat3 ry(glm::vec3(cy, 0, -sy), glm::vec3(0, 1, 0), glm::vec3(sy, 0, cy));
  const glm::mat3 rz(glm::vec3(cz, sz, 0), glm::vec3(-sz, cz, 0), glm::vec3(0, 0, 1));
  return rz * ry * rx;
}

SelectionMask select_box(const SelectionPoints& pts, const SelectionBox& box) {
  for (int k = 0; k < 3; ++k)
    if (!(box.half_extent[k] >= 0.0f) || !std::isfinite(box.half_extent[k]))
      throw Error("box", "half extents must be finite numbers >= 0");
  // Rotation columns are orthonormal: world -> box coordinates is the transpose.
  const glm::mat3 to_box = glm::transpose(box.rotation);
  SelectionMask out(pts.size(), 0);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::vec3 q = to_box * (pts.position[i] - box.centre);
    out[i] = std::abs(q.x) <= box.half_extent.x && std::abs(q.y) <= box.half_extent.y &&
             std::abs(q.z) <= box.half_extent.z;
  }
  return out;
}

SelectionMask select_by_colour(const SelectionPoints& pts, const glm::vec3& reference, float max_distance) {
  if (!(max_distance >= 0.0f)) throw Error("colour", "the colour distance must be >= 0");
  SelectionMask out(pts.size(), 0);
  const float d2 = max_distance * max_distance;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::vec3 d = pts.color[i] - reference;
    out[i] = glm::dot(d, d) <= d2;
  }
  return out;
}

}  // namespace goris
