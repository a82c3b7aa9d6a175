#include "ui/document/removal_session.h"

#include <cstdio>

#include "core/io/dataset.h"
#include "core/util/error.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {
constexpr const char* kCancelledLine = "cancelled; the run folder is consistent: Remove again resumes";
}  // namespace

void RemovalSession::start(const fs::path& run_dir, const RemovalOptions& options) {
  if (const JobState s = job_.state(); job_active(s))
    throw Error(std::string("removal is ") + job_state_name(s) + ": wait for it or cancel it first");
  if (run_dir.empty()) throw Error("remove: no run folder (train a model or open a run first)");
  const fs::path dir = fs::absolute(run_dir);
  progress_.set(RemovalProgressTracker());
  report_.set(std::nullopt);
  run_dir_.set(dir);
  job_.start([this, dir, options](const std::atomic<bool>& stop) { return work(dir, options, stop); });
}

void RemovalSession::cancel() {
  job_.set_cancelled_status(kCancelledLine);
  job_.cancel("cancelling: the current step stops at its next check");
  progress_.with([](RemovalProgressTracker& p) { p.freeze(); });
}

// Under the job's StopRule::Cancels: whatever happens once the stop flag is up (the 2D inpainting stops by
// throwing) ends the run as cancelled.
std::string RemovalSession::work(const fs::path& run_dir, const RemovalOptions& options,
                                 const std::atomic<bool>& stop) {
  {
    // The cost model of the ETA: views, fine-tune length and the optional steps of this run.
    const TrainConfig config = read_run_config(run_dir);
    const Dataset ds = load_dataset(config.input.data, dataset_options(config));
    const int iters =
        options.finetune_iterations > 0 ? options.finetune_iterations : std::max(100, config.scaled_iteration(4000));
    const bool intrinsic = config.mode == TrainMode::Intrinsic;
    const RemovalCostModel cost = RemovalCostModel::estimate(
        ds.train.size(), iters, intrinsic && !options.ablate.count("lamask"), intrinsic && !options.ablate.count("material"));
    progress_.with([&](RemovalProgressTracker& p) {
      p = RemovalProgressTracker(cost);
      if (job_.state() == JobState::Cancelling) p.freeze();
    });
    job_.set_status("removing in " + run_dir.string());
  }
  const RemovalReport report = run_removal(
      run_dir, options,
      [this](const RemovalProgress& p) {
        progress_.with([&](RemovalProgressTracker& t) { t.update(p, job_.elapsed_s()); });
        job_.set_status(std::string(removal_step_name(p.step)) + (p.detail.empty() ? "" : ": " + p.detail));
      },
      &stop);
  report_.set(report);
  if (report.cancelled) throw JobCancelled(kCancelledLine);
  char line[256];
  std::snprintf(line, sizeof line, "done: %zu Gaussians removed, %zu added, %d fine-tune iterations -> %s",
                report.selected, report.added, report.finetune_iterations, report.out_dir.string().c_str());
  std::string status = line;
  if (!report.finetune_restarted.empty())
    status += " (the fine-tune started over: the earlier one was made from other inputs, changed: " +
              report.finetune_restarted + ")";
  return status;
}

}  // namespace goris::ui
