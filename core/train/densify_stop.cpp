#include "core/train/densify_stop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace goris {

DensifyStopPlan densify_stop_plan(const TrainConfig& config, int densify_until, bool intrinsic) {
  const DensifySettings& ds = config.densify;
  DensifyStopPlan p;
  p.adaptive = ds.stop == "adaptive";
  p.from = ds.from_iter;
  p.until = densify_until;
  p.densify_interval = std::max(ds.interval, 1);
  // A full-schedule number like the warm-up: a 2K run checks every 33 iterations, a 30K run every 500.
  p.check_interval = std::max(config.scaled_iteration(ds.stop_check_interval), 1);
  p.reset_interval = std::max(config.opacity_reset_every(), 1);
  p.shading_from = intrinsic ? config.shading_from() : 0;
  p.window = ds.stop_window;
  p.min_gain = ds.stop_min_gain;
  p.holdout_every = ds.holdout_every;
  p.min_steps = ds.stop_min_steps;
  // The schedule alone (no stop yet): where the rule first has window + 1 checks, and how many
  // densification steps it could turn into prune-only steps from there (the check comes first).
  auto next_multiple = [](int it, int base, int step) { return base + (it - base + step - 1) / step * step; };
  int it = p.from;
  for (int seen = 0; it <= p.until; ++it) {
    it = std::min({next_multiple(it, p.from, p.check_interval), next_multiple(it, 0, p.densify_interval), p.until});
    if (++seen == p.window + 1) break;
  }
  if (it <= p.until) {
    p.earliest_stop = it;
    p.skippable_steps = p.until / p.densify_interval - (it - 1) / p.densify_interval;
  }
  return p;
}

std::string DensifyStopPlan::inactive_reason() const {
  // A run without densification (a stage-2 fine-tune under a copied configuration) has nothing to explain.
  if (!adaptive || active() || until < from) return {};
  return std::to_string(skippable_steps) + " densification step(s) after the earliest possible stop (iteration " +
         std::to_string(earliest_stop) + "), fewer than densify_stop_min_steps = " + std::to_string(min_steps) +
         ": holding views out would cost more than it could save, so this run densifies as with fixed";
}

bool DensifyStopPlan::holds_out(int it, const DensifyStopState& s) const {
  return active() && !s.stopped() && it <= until;
}

bool DensifyStopPlan::checks_at(int it, const DensifyStopState& s) const {
  if (!active() || s.stopped() || it < from || it > until) return false;
  // Every check_interval from `from`, each densification step, and the window's last iteration.
  return (it - from) % check_interval == 0 || it % densify_interval == 0 || it == until;
}

int DensifyStopPlan::incomparable_before(int it) const {
  int last = 0;
  // Opacity resets happen at multiples of reset_interval r with r <= until and r + densify_interval <= until
  // (Trainer::step); the latest one before `it`.
  for (int r = ((it - 1) / reset_interval) * reset_interval; r > 0; r -= reset_interval)
    if (r + densify_interval <= until) {
      last = r;
      break;
    }
  if (shading_from > 0 && shading_from < it) last = std::max(last, shading_from);
  return last;
}

std::optional<double> held_out_gain(const std::vector<HeldOutCheck>& checks, int since, int window) {
  std::vector<double> h;
  for (const HeldOutCheck& c : checks)
    if (c.iteration > since) h.push_back(c.psnr);
  if (window < 1 || h.size() <= size_t(window)) return std::nullopt;
  const auto split = h.end() - window;
  return *std::max_element(split, h.end()) - *std::max_element(h.begin(), split);
}

namespace {

std::string history_text(const std::vector<HeldOutCheck>& checks, size_t last_n) {
  std::string out;
  const size_t first = checks.size() > last_n ? checks.size() - last_n : 0;
  for (size_t i = first; i < checks.size(); ++i) {
    char b[48];
    std::snprintf(b, sizeof b, "%s%.2f", out.empty() ? "" : " -> ", checks[i].psnr);
    out += b;
  }
  return (first > 0 ? "... " : "") + out + " dB";
}

}  // namespace

std::string record_held_out_check(DensifyStopState& state, const DensifyStopPlan& plan, int it, double psnr,
                                  std::size_t gaussians) {
  state.checks.push_back({it, std::min(psnr, 99.0), std::uint64_t(gaussians)});
  const std::optional<double> gain = held_out_gain(state.checks, plan.incomparable_before(it), plan.window);
  char line[512];
  if (gain && *gain < plan.min_gain) {
    state.stopped_at = it;
    std::snprintf(line, sizeof line,
                  "adaptive densification: stopped at iteration %d with %zu Gaussians (held-out PSNR %s; the last %d "
                  "checks gained %+.3f dB < %.3f dB); pruning only until iteration %d, held-out views rejoin training",
                  it, gaussians, history_text(state.checks, size_t(plan.window) + 3).c_str(), plan.window, *gain,
                  plan.min_gain, plan.until);
    return line;
  }
  if (it == plan.until) {
    std::snprintf(line, sizeof line,
                  "adaptive densification: no stop before the end of the window (iteration %d, %zu Gaussians, held-out "
                  "PSNR %s); held-out views rejoin training",
                  it, gaussians, history_text(state.checks, size_t(plan.window) + 3).c_str());
    return line;
  }
  return {};
}

nlohmann::json densify_stop_json(const DensifyStopState& state, const DensifyStopPlan& plan,
                                 const std::vector<std::string>& held_out_names) {
  nlohmann::json checks = nlohmann::json::array();
  for (const HeldOutCheck& c : state.checks)
    checks.push_back({{"iteration", c.iteration}, {"held_out_psnr", c.psnr}, {"gaussians", c.gaussians}});
  nlohmann::json j = {{"densify_stop", plan.adaptive ? "adaptive" : "fixed"},
                      {"held_out_views", held_out_names},
                      {"window_from", plan.from},
                      {"window_until", plan.until},
                      {"check_interval", plan.check_interval},
                      {"stop_window", plan.window},
                      {"stop_min_gain_db", std::round(plan.min_gain * 1e6) / 1e6},  // the float key, not 0.100000001
                      {"inactive_reason", plan.inactive_reason().empty() ? nlohmann::json() : nlohmann::json(plan.inactive_reason())},
                      {"earliest_stop", plan.earliest_stop},
                      {"skippable_steps", plan.skippable_steps},
                      {"checks", checks},
                      {"stopped_at", nullptr},
                      {"gaussians_at_stop", nullptr}};
  if (state.stopped()) {
    j["stopped_at"] = state.stopped_at;
    for (const HeldOutCheck& c : state.checks)
      if (c.iteration == state.stopped_at) j["gaussians_at_stop"] = c.gaussians;
  }
  return j;
}

}  // namespace goris
