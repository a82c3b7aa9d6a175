#pragma once
// The adaptive Gaussian budget (DensifySettings::stop = "adaptive": model no more than a scene
// needs): stop densifying once the PSNR of a few held-out training views stops improving. Here: the
// schedule of one run (which iterations hold views out, which measure them), the stop rule, and the record
// that every checkpoint keeps so a resumed run decides exactly as an uninterrupted one. The views
// themselves are chosen and rendered in core/train/held_out_views.h.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/train/train_config.h"

namespace goris {

struct HeldOutCheck {
  int iteration = 0;
  double psnr = 0;  // mean over the held-out views, dB
  std::uint64_t gaussians = 0;
};

// What an adaptive run has measured and decided so far.
struct DensifyStopState {
  std::vector<HeldOutCheck> checks;
  int stopped_at = 0;  // the iteration whose check stopped densification; 0 = not stopped
  bool stopped() const { return stopped_at > 0; }
};

// The schedule of one run, from its configuration.
struct DensifyStopPlan {
  bool adaptive = false;
  int from = 0, until = 0;    // densification steps lie in [from, until] (none when until < from)
  int densify_interval = 1;
  int check_interval = 1;     // stop_check_interval scaled to the run's length
  int reset_interval = 1;     // opacity resets (as the trainer does them: inside the window, followed by a step)
  int shading_from = 0;       // intrinsic: the last warm-up iteration (shading starts after it); 0 = none
  int window = 2;
  double min_gain = 0.1;
  int holdout_every = 8;
  int earliest_stop = 0;     // the first check at which the rule can decide (window + 1 checks in); 0 = none
  int skippable_steps = 0;   // densification steps at or after earliest_stop
  int min_steps = 1;

  // Adaptive, and enough densification steps to skip to be worth holding views out.
  bool active() const { return adaptive && skippable_steps >= min_steps; }
  // Why an adaptive run with densification acts as a fixed one (empty when it does not, and for runs that
  // do not densify at all).
  std::string inactive_reason() const;
  // Whether a new epoch started at iteration `it` leaves the held-out views out: from the start until the
  // stop, or until the window closes.
  bool holds_out(int it, const DensifyStopState& s) const;
  // Whether iteration `it` ends with a held-out check (before that iteration's densification step): every
  // check_interval from `from`, at each densification step and at `until`, while not stopped.
  bool checks_at(int it, const DensifyStopState& s) const;
  // The last event before iteration `it` that makes held-out PSNRs incomparable across it: an opacity
  // reset (the images go nearly transparent and recover) or the end of the intrinsic warm-up (the
  // renderer starts shading). Checks at or before it are not compared with later ones; 0 = none.
  int incomparable_before(int it) const;
};

// `densify_until`: Trainer::densify_until(); `intrinsic`: whether the trainer runs in intrinsic mode.
DensifyStopPlan densify_stop_plan(const TrainConfig& config, int densify_until, bool intrinsic);

// The stop rule on the checks taken after iteration `since` (oldest first), h_0 .. h_{k-1}: with more than
// `window` of them, gain = max(h_{k-window} .. h_{k-1}) - max(h_0 .. h_{k-window-1}), i.e. how much the last
// `window` checks beat the best before them (robust to one noisy check, negative after a drop). nullopt
// while too few checks are comparable.
std::optional<double> held_out_gain(const std::vector<HeldOutCheck>& checks, int since, int window);

// Records the check of iteration `it` and applies the rule (stops when gain < min_gain). Returns a line
// for the user when this check stopped densification, or when the window closed without a stop; empty
// otherwise.
std::string record_held_out_check(DensifyStopState& state, const DensifyStopPlan& plan, int it, double psnr,
                                  std::size_t gaussians);

// The record as RUN/densify_stop.json: settings, held-out view names, every check and the decision.
nlohmann::json densify_stop_json(const DensifyStopState& state, const DensifyStopPlan& plan,
                                 const std::vector<std::string>& held_out_names);

}  // namespace goris
