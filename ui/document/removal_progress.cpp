#include "ui/document/removal_progress.h"

#include <algorithm>

namespace goris::ui {

RemovalCostModel RemovalCostModel::estimate(std::size_t views, int finetune_iterations, bool lighting_masks,
                                            bool material_maps) {
  const double v = double(std::max<std::size_t>(views, 1));
  RemovalCostModel c;
  c.weight[int(RemovalStep::Selection)] = 0.5;
  c.weight[int(RemovalStep::LightingMasks)] = lighting_masks ? v : 0.05;  // one traced render per view
  c.weight[int(RemovalStep::InpaintMasks)] = 0.6 * v;                     // two rasterizations per view
  c.weight[int(RemovalStep::ReferenceViews)] = 0.05;
  c.weight[int(RemovalStep::Inpaint2D)] = 3.0 * (material_maps ? 6.0 : 2.0) * 0.4;  // 3 views x maps
  c.weight[int(RemovalStep::Lift)] = 0.5;
  // An iteration (forward + backward, losses, optimiser) costs about three renders; + loading the images.
  c.weight[int(RemovalStep::FineTune)] = 0.4 * v + 3.0 * double(std::max(finetune_iterations, 1));
  return c;
}

void RemovalProgressTracker::update(const RemovalProgress& p, double now_s) {
  const int k = int(p.step);
  if (k < 0 || k >= kRemovalStepCount) return;
  RemovalStepStatus& s = steps_[std::size_t(k)];
  if (frozen_ && p.done >= p.total) return;
  if (!s.started) {
    s.started = true;
    s.start_s = now_s;
    // The step before ends where this one starts.
    if (current_ >= 0 && current_ != k) {
      RemovalStepStatus& prev = steps_[std::size_t(current_)];
      prev.seconds = now_s - prev.start_s;
    }
  }
  current_ = k;
  s.total = std::max<std::size_t>(p.total, 1);
  s.done = std::min(p.done, s.total);
  if (!p.detail.empty() || s.done == 0) s.detail = p.detail;
  if (s.done >= s.total) s.complete = true;
  s.seconds = now_s - s.start_s;
}

bool RemovalProgressTracker::all_complete() const {
  return std::all_of(steps_.begin(), steps_.end(), [](const RemovalStepStatus& s) { return s.complete; });
}

double RemovalProgressTracker::fraction() const {
  double sum = 0, total = 0;
  for (int k = 0; k < kRemovalStepCount; ++k) {
    sum += cost_.weight[std::size_t(k)] * steps_[std::size_t(k)].fraction();
    total += cost_.weight[std::size_t(k)];
  }
  return total > 0 ? sum / total : 0.0;
}

double RemovalProgressTracker::eta_s(double now_s) const {
  const double f = fraction();
  if (all_complete()) return 0.0;
  if (f < 0.01 || now_s <= 0) return -1.0;
  return now_s * (1.0 - f) / f;
}

}  // namespace goris::ui
