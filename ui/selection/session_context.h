#pragma once
// What the selection worker prepares once per model (ui/selection/selection_session.h): the selection rules' view of
// it, the kNN graph, the picker, and while Gaussians are hidden a copy of the model with them transparent
// (so they hide nothing behind them from the region tools) and a picker that looks through them.
// Worker thread only.
#include <memory>
#include <optional>

#include "core/scene/gaussians.h"
#include "removal/selection/selection_pick.h"
#include "ui/selection/selection_session.h"

namespace goris::ui {

struct SelectionSession::Context {
  std::shared_ptr<const ModelSnapshot> model;
  SelectionModel selection;
  std::unique_ptr<GaussianPicker> picker;

  // The model as the viewports show it: hidden Gaussians transparent. Rebuilt when `hidden` changes.
  const GaussianModel& shown_model(const std::shared_ptr<const SelectionMask>& hidden);
  // The picker of the shown model (`picker` when nothing is hidden).
  const GaussianPicker& shown_picker(const std::shared_ptr<const SelectionMask>& hidden);

 private:
  std::optional<GaussianModel> shown_;
  std::shared_ptr<const SelectionMask> shown_hidden_;
  std::unique_ptr<GaussianPicker> shown_picker_;
  std::shared_ptr<const SelectionMask> shown_picker_hidden_;
};

}  // namespace goris::ui
