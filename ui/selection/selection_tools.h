#pragma once
// The selection tools' state in the editor: which tool the main viewport's left button uses, the
// "through everything" toggle, the brush radius, the placed sphere and box, the colour range. No OpenGL or
// ImGui here (the panel and the viewport draw it; ui/panels/tool_bar.h, ui/viewport/viewport_tools.h).
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "ui/selection/region_masks.h"

namespace goris::ui {

// Click: the grown click; Rect / Lasso / Brush: drag a shape on the view; Sphere / Box: place a volume
// (drag its handles), then select inside it.
enum class SelectTool { Click, Rect, Lasso, Brush, Sphere, Box };
const char* select_tool_id(SelectTool t);     // "click", "rect", "lasso", "brush", "sphere", "box"
const char* select_tool_label(SelectTool t);  // "Click", "Rect", ...
std::optional<SelectTool> select_tool_from_id(const std::string& id);

struct SelectionTools {
  SelectTool tool = SelectTool::Click;
  bool through_all = false;   // rect / lasso / brush: every centre inside, not only what the view shows
  float brush_radius = 12.0f;  // window pixels of the main viewport's image
  VolumeRegion sphere{VolumeRegion::Kind::Sphere};
  VolumeRegion box{VolumeRegion::Kind::Box};
  bool volumes_placed = false;  // false: placed at the scene's centre when a volume tool is first chosen
  glm::vec3 colour{0.5f};
  float colour_distance = 0.15f;
  int step_rings = 1;  // grow / shrink step

  bool volume_tool() const { return tool == SelectTool::Sphere || tool == SelectTool::Box; }
  VolumeRegion& volume() { return tool == SelectTool::Box ? box : sphere; }
  // Puts both volumes at `centre` with a size of `radius` (the scene's fifth, say).
  void place_volumes(const glm::vec3& centre, float radius);
};

}  // namespace goris::ui
