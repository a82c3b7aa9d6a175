#pragma once
// Stage-2 progress as the Removal panel shows it: run_removal's RemovalProgress events (step, done, total,
// detail) turned into one status per step (progress, detail, time spent, complete or not), an overall
// fraction and an ETA. The steps cost very different amounts of time (the fine-tune dominates), so the
// overall fraction weights each step by a rough cost model (RemovalCostModel) and the ETA extrapolates
// the time spent so far over that fraction. Nothing here knows about threads or the GUI.
#include <array>
#include <cstddef>
#include <string>

#include "removal/pipeline/removal_pipeline.h"

namespace goris::ui {

struct RemovalStepStatus {
  std::size_t done = 0, total = 1;
  std::string detail;
  bool started = false, complete = false;
  double seconds = 0;  // time in the step so far (all of it once the next step started)
  double start_s = 0;  // when it started (seconds since the removal started)
  float fraction() const { return complete ? 1.0f : total ? float(done) / float(total) : 0.0f; }
};

// Relative cost of the steps (units of "one rendered view", roughly).
struct RemovalCostModel {
  std::array<double, kRemovalStepCount> weight{1, 1, 1, 1, 1, 1, 1};
  // From the number of training views, the fine-tune length and which optional work is done.
  static RemovalCostModel estimate(std::size_t views, int finetune_iterations, bool lighting_masks,
                                   bool material_maps);
};

class RemovalProgressTracker {
 public:
  explicit RemovalProgressTracker(RemovalCostModel cost = {}) : cost_(cost) {}
  // An event at `now_s` seconds since the removal started.
  void update(const RemovalProgress& p, double now_s);
  // After a cancel request: steps may still report, but none counts as complete any more (the pipeline
  // finishes the step it was in as it stops, which must not read as done).
  void freeze() { frozen_ = true; }

  const std::array<RemovalStepStatus, kRemovalStepCount>& steps() const { return steps_; }
  int current_step() const { return current_; }  // -1 before the first event
  bool all_complete() const;
  double fraction() const;          // overall, 0..1
  double eta_s(double now_s) const;  // seconds left; negative when not known yet

 private:
  RemovalCostModel cost_;
  std::array<RemovalStepStatus, kRemovalStepCount> steps_{};
  int current_ = -1;
  bool frozen_ = false;
};

}  // namespace goris::ui
