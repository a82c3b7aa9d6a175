#pragma once
// The guided two-click flow for a scene trained without object masks (docs/user/editor.md):
//
//   1. click the object in one training view;
//   2. click it in a second view: the flow offers one from another direction (turned 30-100 degrees from
//      the first, showing the first click's object large, where a click at the object's deepest pixel grows
//      the region that agrees best with the first click's mask) and that point;
//   3. review the object masks written for every training view (a stepper over the views, the mask drawn
//      over the main viewport); a click in a reviewed view adds that view's region, or a click can be taken
//      back;
//   4. use them as target masks (AppState::use_as_target_masks) and start the removal.
//
// Every evaluation is `goris select --click`'s own code (removal/selection/selection_click_flow.h) run on the
// selection worker (SelectionSession::click_regions), one undo step of the selection; the flow's undo steps
// back through its clicks (and the target masks), its cancel undoes them all and stops a running removal.
// No ImGui here: the panel (ui/panels/two_click_panel.h), the main viewport and scripts drive it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/selection_points.h"
#include "ui/selection/flow_result.h"

namespace goris::ui {

class AppState;

enum class FlowStep { Off, FirstClick, SecondClick, Review, Removing, Done };
const char* flow_step_name(FlowStep s);  // "off", "first click", ...

class TwoClickFlow {
 public:
  FlowStep step() const { return step_; }
  bool active() const { return step_ != FlowStep::Off; }
  // An evaluation, an undo or the target masks are under way.
  bool busy() const { return pending_.kind != Pending::None; }
  const FlowProgress& progress() const { return *progress_; }
  // The latest evaluation (null before the first click).
  const std::shared_ptr<const FlowResult>& result() const { return result_; }
  const std::vector<FlowClick>& clicks() const { return clicks_; }
  std::size_t undo_steps() const { return entries_.size(); }
  // The training view under review (step 3).
  std::size_t review_view() const { return review_view_; }
  std::filesystem::path masks_dir(const AppState& st) const;  // RUN/two_click_masks

  // Step 1 on the main viewport: snapped to training view `view` (default: the snapped training view, else
  // the first). Throws goris::Error when selecting is blocked or the scene has no training views.
  void start(AppState& st, std::optional<std::size_t> view = std::nullopt);
  // Snaps the main viewport to another training view for the next click (steps 1 and 2) or the review.
  void show_view(AppState& st, std::size_t view);
  // A click at (x, y) of the main viewport's image shown at `display` (window pixels), which must show a
  // training view: steps 1 and 2 take it as the next click, the review as a fix (the reviewed view's region
  // is added). Returns the selection job (0: nothing submitted).
  std::uint64_t click(AppState& st, float x, float y, glm::vec2 display);
  // The click the flow offers in step 2 (snapping to its view).
  std::uint64_t click_offered(AppState& st);
  // Review fix: evaluates again without click `index`.
  std::uint64_t remove_click(AppState& st, std::size_t index);
  // Back one step: the last evaluation or the target masks (a running removal is cancelled first; while
  // an evaluation runs it is cancelled instead). Returns the selection job (0: none).
  std::uint64_t undo(AppState& st);
  // Undoes every step of the flow and leaves it.
  void cancel(AppState& st);
  // Step 4: the target masks from the reviewed selection, then the removal (`iterations` fine-tune
  // iterations; 0: the panel's).
  std::uint64_t use_and_remove(AppState& st, int iterations = 0);
  // Once per frame (AppState::poll): takes in finished jobs, starts the removal after the target masks,
  // follows the removal and leaves the flow when the model changes under it.
  void sync(AppState& st);

 private:
  struct Pending {
    enum Kind { None, Evaluate, Undo, TargetMasks } kind = None;
    std::uint64_t job = 0;
    std::vector<FlowClick> clicks;
    std::shared_ptr<FlowResult> result;
  };
  // One undo step of the flow: the selection it pushed and what the flow showed before it.
  struct Entry {
    bool target_masks = false;
    std::shared_ptr<const SelectionMask> selection;
    std::vector<FlowClick> clicks_before;
    std::shared_ptr<const FlowResult> result_before;
    FlowStep step_before = FlowStep::Off;
  };
  std::uint64_t evaluate(AppState& st, std::vector<FlowClick> clicks);
  void after_evaluation(AppState& st);
  FlowStep step_for(std::size_t clicks) const;

  FlowStep step_ = FlowStep::Off;
  std::vector<FlowClick> clicks_;
  std::shared_ptr<const FlowResult> result_;
  std::vector<Entry> entries_;
  Pending pending_;
  std::shared_ptr<FlowProgress> progress_ = std::make_shared<FlowProgress>();
  std::size_t review_view_ = 0;
  bool cancelling_ = false;  // cancel(): undo everything once nothing runs
  int removal_iterations_ = 0;
  const void* model_ = nullptr;  // the model the flow runs on
  // The run's glossy masks, read from disk by the first evaluation of a flow and shared by the later ones
  // (each runs on the selection worker; start() begins a new cache).
  struct GlossyCache {
    std::mutex mutex;
    bool read = false;
    std::shared_ptr<const std::vector<std::vector<float>>> masks;
  };
  std::shared_ptr<GlossyCache> glossy_ = std::make_shared<GlossyCache>();
};

}  // namespace goris::ui
