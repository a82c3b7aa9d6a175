#include "ui/selection/selection_tools.h"

namespace goris::ui {

namespace {
struct ToolName {
  SelectTool tool;
  const char *id, *label;
};
constexpr ToolName kTools[] = {{SelectTool::Click, "click", "Click"},   {SelectTool::Rect, "rect", "Rect"},
                               {SelectTool::Lasso, "lasso", "Lasso"},   {SelectTool::Brush, "brush", "Brush"},
                               {SelectTool::Sphere, "sphere", "Sphere"}, {SelectTool::Box, "box", "Box"}};
}  // namespace

const char* select_tool_id(SelectTool t) {
  for (const ToolName& n : kTools)
    if (n.tool == t) return n.id;
  return "click";
}

const char* select_tool_label(SelectTool t) {
  for (const ToolName& n : kTools)
    if (n.tool == t) return n.label;
  return "Click";
}

std::optional<SelectTool> select_tool_from_id(const std::string& id) {
  for (const ToolName& n : kTools)
    if (id == n.id) return n.tool;
  return std::nullopt;
}

void SelectionTools::place_volumes(const glm::vec3& centre, float radius) {
  sphere.centre = box.centre = centre;
  sphere.radius = radius;
  box.half_extent = glm::vec3(radius);
  box.rotation_degrees = glm::vec3(0.0f);
  volumes_placed = true;
}

}  // namespace goris::ui
