#pragma once
// Opening a data set or a run folder: a path field, the recent paths, what is open.
#include <string>

#include "ui/panels/panel.h"

namespace goris::ui {

class OpenPanel final : public Panel {
 public:
  const char* title() const override { return "Open"; }
  void draw(AppState& state) override;

 private:
  std::string path_;
};

}  // namespace goris::ui
