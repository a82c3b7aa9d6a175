#pragma once
// Curves of the training session: loss, PSNR, Gaussian count and iterations per second.
#include "ui/panels/panel.h"

namespace goris::ui {

class PlotsPanel final : public Panel {
 public:
  const char* title() const override { return "Plots"; }
  bool visible(const StudioSettings& s) const override { return s.show_plots; }
  void draw(AppState& state) override;
};

}  // namespace goris::ui
