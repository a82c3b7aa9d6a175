#pragma once
// The Selection panel's tools (docs/user/editor.md): the tool bar (click, rect, lasso, brush, sphere,
// box), the "through everything" toggle and brush radius, the volume's numeric fields, the colour range,
// invert, grow / shrink steps, hide / lock, and "Use as target masks". Every button goes through AppState.
#include <optional>
#include <string>

#include "ui/document/app_state.h"
#include "ui/document/panel_layout.h"

namespace goris::ui {

void draw_selection_tools(AppState& st);

// Where the tool bar drew the button (or tool) with this label in its last frame, in window pixels:
// "Invert", "Grow step", "Sphere", ...; the Select / Add / Subtract buttons of the volume and the colour
// range are "volume Select", "colour Add", .... Nullopt when it was not drawn (the panel or the section is
// collapsed). Scripts press them (`press LABEL`).
std::optional<Rect> tool_bar_button(const std::string& label);

}  // namespace goris::ui
