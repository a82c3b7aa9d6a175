#pragma once
// A section of the sidebar. The editor keeps a list of panels and draws each as a collapsing header, so a
// new workflow step (selection, removal, export) is one more class added to that list
// (see StudioApp::StudioApp).
#include <functional>

#include "core/util/error.h"
#include "ui/document/app_state.h"

namespace goris::ui {

class Panel {
 public:
  virtual ~Panel() = default;
  virtual const char* title() const = 0;
  virtual bool open_by_default() const { return true; }
  // Whether the sidebar shows it at all (View menu toggles).
  virtual bool visible(const StudioSettings&) const { return true; }
  // Draws the panel's contents (inside the sidebar window, under its header).
  virtual void draw(AppState& state) = 0;
};

// Runs a panel's action; a goris::Error it throws goes to the status bar (nothing escapes into the frame).
inline void report_errors(AppState& state, const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    state.message(e.what(), true);
  }
}

}  // namespace goris::ui
