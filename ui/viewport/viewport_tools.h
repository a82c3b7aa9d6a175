#pragma once
// The selection tools on the main viewport (ui/selection/selection_tools.h): a left drag draws a rectangle,
// a lasso or a brush stroke and selects what it covers when the button is released (Shift adds, Ctrl
// removes); the Sphere and Box tools draw their volume and its handles (the centre moves in the view's
// plane, the others resize). Alt+drag still orbits. ImGui only; the edits go through AppState.
#include <vector>

#include <glm/glm.hpp>

#include "ui/document/app_state.h"
#include "ui/document/panel_layout.h"

namespace goris::ui {

class ViewportTools {
 public:
  // Called by the main viewport after its image button: `image` is where the image lies (window pixels).
  // Returns true when the tool took the left button this frame (the viewport then neither orbits nor picks).
  bool handle_mouse(AppState& st, const Rect& image);
  // The shape being drawn, the brush cursor, the volume and its handles.
  void draw_overlay(AppState& st, const Rect& image) const;

  enum class Handle { None, Centre, Radius, AxisX, AxisY, AxisZ };
  // Window positions of the volume's handles, those in front of the camera (scripts drag them too).
  std::vector<std::pair<Handle, glm::vec2>> handles(const AppState& st, const Rect& image) const;

 private:
  void drag_handle(AppState& st, const Rect& image, glm::vec2 delta);
  void finish_shape(AppState& st, const Rect& image);

  bool drawing_ = false;
  Handle dragging_ = Handle::None;
  std::vector<glm::vec2> points_;  // window pixels, relative to the image's corner
};

}  // namespace goris::ui
