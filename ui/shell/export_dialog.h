#pragma once
// The Export dialog (File > Export..., the Removal panel's Export button): what to export from the current
// run or its cleaned scene (intrinsic PLY, baked PLY with its distillation length, renders of the test /
// training views or an orbit), where (path fields remembered in the settings; relative paths lie inside the
// exported run folder), an Export button that runs AppState::start_export on the export worker, a progress
// bar per part and overall, Cancel / Finish distilling now, and the outcome: the paths written, or the
// error naming the file and the problem. A floating window, not a modal: the editor stays usable meanwhile.
#include <string>

#include "ui/document/app_state.h"

namespace goris::ui {

class ExportDialog {
 public:
  // Draws the dialog while state.show_export_dialog is set; closing it clears the flag (an export that
  // runs goes on; its end is reported in the status bar).
  void draw(AppState& state);

 private:
  void draw_choices(AppState& st, bool active);
  void draw_buttons(AppState& st, bool active);
  void draw_progress(AppState& st);
  void draw_outcome(AppState& st);

  std::string refused_;  // why the last press of Export was refused (cleared by the next press)
};

}  // namespace goris::ui
