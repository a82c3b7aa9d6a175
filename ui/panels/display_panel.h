#pragma once
// What the viewports show: how many grid tiles, the render resolution cap, the label overlay and the
// comparison with the input photo of the nearest training camera.
#include "ui/panels/panel.h"

namespace goris::ui {

class DisplayPanel final : public Panel {
 public:
  const char* title() const override { return "Display"; }
  void draw(AppState& state) override;
};

}  // namespace goris::ui
