#pragma once
// Selecting the target (docs/user/editor.md): what is selected, the tools (ui/panels/tool_bar.h), the grow /
// shrink slider, selection by the learned labels or the data set's object masks, clear, undo / redo, and
// saving RUN/selection.json. Clicks and drags in the main viewport select too (plain: replace, shift: add,
// ctrl: remove).
#include "ui/panels/panel.h"

namespace goris::ui {

class SelectionPanel final : public Panel {
 public:
  const char* title() const override { return "Selection"; }
  void draw(AppState& state) override;

 private:
  float grow_ = kDefaultGrow;  // the slider while it is dragged
  bool dragging_ = false, drag_edited_ = false;
};

}  // namespace goris::ui
