#pragma once
// Stage-1 training: options of a new run, the run folder, start / pause / resume / stop, and the numbers
// (iteration, loss, PSNR, Gaussians, iterations/s, ETA).
#include <string>

#include "ui/panels/panel.h"

namespace goris::ui {

class TrainingPanel final : public Panel {
 public:
  const char* title() const override { return "Training"; }
  void draw(AppState& state) override;

 private:
  std::string run_folder_;       // the field's text
  std::string seen_run_folder_;  // the state's folder when the field last took it over
};

}  // namespace goris::ui
