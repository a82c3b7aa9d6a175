#pragma once
// The view camera: orbit or fly, field of view, and the data set's cameras to snap to.
#include "ui/panels/panel.h"
#include "ui/viewport/viewport.h"

namespace goris::ui {

class CamerasPanel final : public Panel {
 public:
  explicit CamerasPanel(CameraMode& mode) : mode_(mode) {}
  const char* title() const override { return "Camera"; }
  void draw(AppState& state) override;

 private:
  CameraMode& mode_;
};

}  // namespace goris::ui
