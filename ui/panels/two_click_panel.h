#pragma once
// The guided two-click flow (ui/document/two_click_flow.h) as a step-by-step panel: the four steps with
// the current one marked, the view chooser for the clicks, the view offered for the second click, the
// review's stepper and strip over every training view's mask (the mask itself is drawn over the main
// viewport), the progress of the running step, Undo step and Cancel.
#include "ui/panels/panel.h"

namespace goris::ui {

class TwoClickPanel final : public Panel {
 public:
  const char* title() const override { return "Two-click"; }
  bool open_by_default() const override { return false; }
  void draw(AppState& state) override;
};

}  // namespace goris::ui
