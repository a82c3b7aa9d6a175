#pragma once
// Opening a data set or a run folder: a path field, the recent paths, what is open. A folder of photos
// without a data set, or a video file, is offered for import (COLMAP, ui/document/capture_job.h) instead: the
// capture options, a progress bar per stage with an ETA, Cancel, errors, and the report once the new data
// set is open.
#include <string>

#include "ui/panels/panel.h"

namespace goris::ui {

class OpenPanel final : public Panel {
 public:
  const char* title() const override { return "Open"; }
  void draw(AppState& state) override;

 private:
  void draw_import(AppState& state);
  void draw_import_progress(const AppState& state);

  std::string path_;
  std::string checked_path_;  // the path whose kind `importable_` says
  bool importable_ = false;
};

}  // namespace goris::ui
