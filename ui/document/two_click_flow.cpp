#include "ui/document/two_click_flow.h"

#include <cstdio>

#include "core/util/error.h"
#include "train/setup/auto_mode.h"
#include "ui/document/app_state.h"

namespace goris::ui {

namespace fs = std::filesystem;

const char* flow_step_name(FlowStep s) {
  switch (s) {
    case FlowStep::Off:
      return "off";
    case FlowStep::FirstClick:
      return "first click";
    case FlowStep::SecondClick:
      return "second click";
    case FlowStep::Review:
      return "review";
    case FlowStep::Removing:
      return "removing";
    case FlowStep::Done:
      return "done";
  }
  return "";
}

namespace {

const std::vector<View>& train_views(const AppState& st, const char* what) {
  const OpenedScene* s = st.scene();
  if (!s || !s->dataset || s->dataset->train.empty())
    throw Error(std::string("two-click: ") + what + ": no training views (open a run whose data set is there)");
  return s->dataset->train;
}

void require_selectable(const AppState& st, const char* what) {
  if (const char* why = st.selection_blocked()) throw Error(std::string("two-click: ") + what + ": " + why);
}

}  // namespace

fs::path TwoClickFlow::masks_dir(const AppState& st) const {
  const fs::path run = st.current_run();
  return run.empty() ? fs::path() : run / "two_click_masks";
}

FlowStep TwoClickFlow::step_for(std::size_t clicks) const {
  return clicks == 0 ? FlowStep::FirstClick : clicks == 1 ? FlowStep::SecondClick : FlowStep::Review;
}

void TwoClickFlow::start(AppState& st, std::optional<std::size_t> view) {
  require_selectable(st, "start");
  const std::vector<View>& views = train_views(st, "start");
  if (st.current_run().empty()) throw Error("two-click: start: the model has no run folder (train it, or open a run)");
  if (busy()) throw Error("two-click: start: the flow is still working (cancel it first)");
  const std::size_t v = view ? *view : st.snapped && !st.snapped_test ? st.snapped_index : 0;
  if (v >= views.size()) throw Error("two-click: start: there is no training view " + std::to_string(v));
  st.snap(v, false);
  step_ = FlowStep::FirstClick;
  clicks_.clear();
  entries_.clear();
  result_.reset();
  cancelling_ = false;
  model_ = st.model().get();
  glossy_ = std::make_shared<GlossyCache>();  // another run's masks, or the same run's written again
  review_view_ = v;
  st.message("two-click: 1. click the object in " + views[v].name + " (or choose another view)");
}

void TwoClickFlow::show_view(AppState& st, std::size_t view) {
  if (!active()) throw Error("two-click: the flow is not running (start it first)");
  const std::vector<View>& views = train_views(st, "view");
  if (view >= views.size()) throw Error("two-click: there is no training view " + std::to_string(view));
  st.snap(view, false);
  if (step_ == FlowStep::Review) review_view_ = view;
}

std::uint64_t TwoClickFlow::click(AppState& st, float x, float y, glm::vec2 display) {
  if (step_ != FlowStep::FirstClick && step_ != FlowStep::SecondClick && step_ != FlowStep::Review)
    throw Error(std::string("two-click: no click is asked for now (") + flow_step_name(step_) + ")");
  if (busy()) throw Error("two-click: wait until the flow's last step is done");
  const std::vector<View>& views = train_views(st, "click");
  if (!st.snapped || st.snapped_test || st.snapped_index >= views.size())
    throw Error("two-click: click on a training view: choose one with the flow's view buttons (the view moved)");
  if (!st.frame || !(display.x > 0 && display.y > 0))
    throw Error("two-click: click: the main viewport shows no image yet");
  const View& v = views[st.snapped_index];
  if (st.frame->camera.R != v.camera.R || st.frame->camera.t != v.camera.t)
    throw Error("two-click: click: the view is still being drawn, click again");
  if (x < 0 || y < 0 || x >= display.x || y >= display.y)
    throw Error("two-click: click: (" + std::to_string(x) + ", " + std::to_string(y) + ") lies outside the image");
  // Window pixels -> the training view's pixels (the frame is the training camera resized).
  FlowClick c;
  c.view = st.snapped_index;
  c.x = std::min(v.camera.width - 1, int((x + 0.5f) * float(v.camera.width) / display.x));
  c.y = std::min(v.camera.height - 1, int((y + 0.5f) * float(v.camera.height) / display.y));
  std::vector<FlowClick> clicks = clicks_;
  clicks.push_back(c);
  return evaluate(st, std::move(clicks));
}

std::uint64_t TwoClickFlow::click_offered(AppState& st) {
  if (step_ != FlowStep::SecondClick) throw Error("two-click: a second view is offered after the first click only");
  if (!result_ || !result_->offered)
    throw Error("two-click: no other view shows the first click's object well: choose a view and click");
  if (busy()) throw Error("two-click: wait until the flow's last step is done");
  st.snap(result_->offered->view, false);
  std::vector<FlowClick> clicks = clicks_;
  clicks.push_back(*result_->offered);
  return evaluate(st, std::move(clicks));
}

std::uint64_t TwoClickFlow::remove_click(AppState& st, std::size_t index) {
  if (step_ != FlowStep::Review) throw Error("two-click: clicks are taken back in the review (step 3)");
  if (busy()) throw Error("two-click: wait until the flow's last step is done");
  if (index >= clicks_.size()) throw Error("two-click: there is no click " + std::to_string(index + 1));
  if (clicks_.size() <= 1) throw Error("two-click: the last click cannot be taken back: undo, or cancel the flow");
  std::vector<FlowClick> clicks = clicks_;
  clicks.erase(clicks.begin() + std::ptrdiff_t(index));
  return evaluate(st, std::move(clicks));
}

std::uint64_t TwoClickFlow::evaluate(AppState& st, std::vector<FlowClick> clicks) {
  require_selectable(st, "select");
  const std::vector<View>& views = train_views(st, "select");
  const fs::path dir = masks_dir(st);
  if (dir.empty()) throw Error("two-click: the model has no run folder to write the masks into");
  auto result = std::make_shared<FlowResult>();
  result->clicks = clicks;
  result->dir = dir;
  progress_->cancel = false;
  progress_->done = 0;
  progress_->total = 0;
  progress_->set_stage("queued");
  SelectionSession::GlossyMasks glossy;
  if (const std::optional<TrainConfig>& config = st.scene()->run_config)
    glossy = [config = *config, views, cache = glossy_]() -> std::shared_ptr<const std::vector<std::vector<float>>> {
      const std::lock_guard<std::mutex> lock(cache->mutex);
      if (cache->read) return cache->masks;
      cache->read = true;
      // They help and are not needed: a run whose detected masks are gone selects without them.
      try {
        cache->masks = std::make_shared<const std::vector<std::vector<float>>>(run_glossy_masks(config, views));
      } catch (const Error& e) {
        std::fprintf(stderr, "two-click: selecting without the run's glossy masks: %s\n", e.what());
      }
      return cache->masks;
    };
  const std::uint64_t job =
      st.selection().click_regions(views, st.scene()->dataset_options, result, progress_, std::move(glossy));
  pending_ = {Pending::Evaluate, job, std::move(clicks), std::move(result)};
  return job;
}

std::uint64_t TwoClickFlow::undo(AppState& st) {
  if (!active()) throw Error("two-click: the flow is not running");
  if (pending_.kind == Pending::Evaluate) {  // the running evaluation is the step taken back
    progress_->cancel = true;
    return pending_.job;
  }
  if (busy()) throw Error("two-click: wait until the flow's last step is done");
  if (step_ == FlowStep::Removing) {
    st.removal().cancel();
    st.message("two-click: cancelling the removal");
    return 0;
  }
  if (step_ == FlowStep::Done) throw Error("two-click: the removal is done (before / after shows the scene with the target)");
  if (entries_.empty()) throw Error("two-click: nothing to undo (cancel leaves the flow)");
  if (st.selection().view().mask != entries_.back().selection)
    throw Error("two-click: the selection was edited outside the flow: undo that in the Selection panel first");
  const std::uint64_t job = st.undo_selection();
  pending_ = {Pending::Undo, job, {}, nullptr};
  return job;
}

void TwoClickFlow::cancel(AppState& st) {
  if (!active()) return;
  progress_->cancel = true;
  if (st.removal().active()) st.removal().cancel();
  cancelling_ = true;
  sync(st);
}

std::uint64_t TwoClickFlow::use_and_remove(AppState& st, int iterations) {
  if (step_ != FlowStep::Review) throw Error("two-click: use the masks after the review (step 3)");
  if (busy()) throw Error("two-click: wait until the flow's last step is done");
  removal_iterations_ = iterations;
  const std::uint64_t job = st.use_as_target_masks({});
  pending_ = {Pending::TargetMasks, job, {}, nullptr};
  return job;
}

void TwoClickFlow::after_evaluation(AppState& st) {
  const std::vector<View>& views = train_views(st, "review");
  char b[256];
  if (step_ == FlowStep::SecondClick) {
    if (result_->offered) {
      const FlowClick& o = *result_->offered;
      st.snap(o.view, false);
      std::snprintf(b, sizeof b, "two-click: 2. click the object in a second view: offered %s (click at (%d, %d))",
                    views[o.view].name.c_str(), o.x, o.y);
    } else {
      std::snprintf(b, sizeof b, "two-click: 2. click the object in a second view (no view was found to offer)");
    }
  } else {
    std::snprintf(b, sizeof b,
                  "two-click: 3. review the masks of the %zu views (%zu of %zu Gaussians selected from %zu clicks)",
                  views.size(), result_->selected, result_->total, clicks_.size());
  }
  st.message(b);
}

void TwoClickFlow::sync(AppState& st) {
  if (!active()) return;
  if (pending_.kind != Pending::None && (pending_.job == 0 || st.selection().finished(pending_.job))) {
    const bool ok = pending_.job != 0 && !st.selection().job_error(pending_.job);
    Pending p = std::move(pending_);
    pending_ = {};
    if (ok && p.kind == Pending::Evaluate) {
      entries_.push_back({false, p.result->selection, clicks_, result_, step_});
      clicks_ = std::move(p.clicks);
      result_ = std::move(p.result);
      step_ = step_for(clicks_.size());
      if (!cancelling_) after_evaluation(st);
    } else if (ok && p.kind == Pending::Undo) {
      const Entry e = std::move(entries_.back());
      entries_.pop_back();
      clicks_ = e.clicks_before;
      result_ = e.result_before;
      step_ = e.step_before == FlowStep::Off ? FlowStep::FirstClick : e.step_before;
      st.message(std::string("two-click: back to the ") + flow_step_name(step_) + " step");
    } else if (ok && p.kind == Pending::TargetMasks) {
      entries_.push_back({true, st.selection().view().mask, clicks_, result_, step_});
      if (!cancelling_) {
        try {
          st.start_removal(removal_iterations_);
          step_ = FlowStep::Removing;
          st.message("two-click: 4. removing the target");
        } catch (const Error& e) {
          st.message(std::string("two-click: the removal did not start: ") + e.what(), true);
        }
      }
    }
  }
  if (step_ == FlowStep::Removing && !st.removal().active()) {
    if (st.removal().state() == JobState::Done) {
      step_ = FlowStep::Done;
      st.message("two-click: done: the cleaned scene is shown (Display: before / after)");
    } else {
      step_ = FlowStep::Review;  // cancelled or failed: the target masks stay, undo takes them back
    }
  }
  if (cancelling_ && !busy() && !st.removal().active()) {
    // Every step of the flow undone, last first (the selection worker runs them in order).
    std::size_t undone = 0;
    if (step_ != FlowStep::Done && !st.selection_blocked())
      for (auto it = entries_.rbegin(); it != entries_.rend(); ++it, ++undone) st.undo_selection();
    step_ = FlowStep::Off;
    clicks_.clear();
    entries_.clear();
    result_.reset();
    cancelling_ = false;
    st.message("two-click: cancelled (" + std::to_string(undone) + " steps undone)");
    return;
  }
  // Another model (another run opened, training went on): the flow's clicks belong to the old one.
  if (step_ != FlowStep::Removing && step_ != FlowStep::Done && st.model().get() != model_ && !busy()) {
    step_ = FlowStep::Off;
    clicks_.clear();
    entries_.clear();
    result_.reset();
    st.message("two-click: the shown model changed, the flow was left");
  }
}

}  // namespace goris::ui
