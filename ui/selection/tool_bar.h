#pragma once
// The Selection panel's tools (docs/user/editor.md): the tool bar (click, rect, lasso, brush, sphere,
// box), the "through everything" toggle and brush radius, the volume's numeric fields, the colour range,
// invert, grow / shrink steps, hide / lock, and "Use as target masks". Every button goes through AppState.
#include "ui/app_state.h"

namespace goris::ui {

void draw_selection_tools(AppState& st);

}  // namespace goris::ui
