#pragma once
// The mouse of the scripted mode's `drag` lines: the runner (ui/script/script_runner.h) plays it one frame at a
// time, the window (ui/shell/studio_window.h) gives it to ImGui in place of the real pointer.
#include <glm/glm.hpp>

namespace goris::ui {

// A mouse the scripted mode drives (`drag`): replaces the real pointer, its left button and the modifier
// keys for the frame it is given to.
struct ScriptedMouse {
  glm::vec2 pos{0.0f};  // window pixels
  bool left_down = false;
  bool shift = false, ctrl = false, alt = false;
};

}  // namespace goris::ui
