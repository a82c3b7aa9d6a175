#include "ui/removal_session.h"

#include <cstdio>

#include "core/io/dataset.h"
#include "core/train/run_folder.h"
#include "core/train/train_setup.h"
#include "core/util/error.h"
#include "ui/background_priority.h"

namespace goris::ui {

namespace fs = std::filesystem;

const char* removal_state_name(RemovalState s) {
  switch (s) {
    case RemovalState::Idle:
      return "idle";
    case RemovalState::Running:
      return "running";
    case RemovalState::Cancelling:
      return "cancelling";
    case RemovalState::Done:
      return "done";
    case RemovalState::Cancelled:
      return "cancelled";
    case RemovalState::Error:
      return "error";
  }
  return "?";
}

RemovalSession::~RemovalSession() {
  cancel();
  if (worker_.joinable()) worker_.join();
}

void RemovalSession::start(const fs::path& run_dir, const RemovalOptions& options) {
  {
    std::lock_guard lk(mutex_);
    if (state_ == RemovalState::Running || state_ == RemovalState::Cancelling)
      throw Error(std::string("removal is ") + removal_state_name(state_) + ": wait for it or cancel it first");
  }
  if (run_dir.empty()) throw Error("remove: no run folder (train a model or open a run first)");
  if (worker_.joinable()) worker_.join();  // it has ended: joining does not wait
  std::lock_guard lk(mutex_);
  state_ = RemovalState::Running;
  status_ = "starting";
  progress_ = RemovalProgressTracker();
  report_.reset();
  run_dir_ = fs::absolute(run_dir);
  started_ = std::chrono::steady_clock::now();
  stop_ = false;
  worker_ = std::thread([this, rd = run_dir_, options] { work(rd, options); });
}

void RemovalSession::cancel() {
  std::lock_guard lk(mutex_);
  if (state_ != RemovalState::Running) return;
  stop_ = true;
  state_ = RemovalState::Cancelling;
  status_ = "cancelling: the current step stops at its next check";
  progress_.freeze();
  changed_.notify_all();
}

RemovalState RemovalSession::state() const {
  std::lock_guard lk(mutex_);
  return state_;
}
bool RemovalSession::active() const {
  const RemovalState s = state();
  return s == RemovalState::Running || s == RemovalState::Cancelling;
}
std::string RemovalSession::status() const {
  std::lock_guard lk(mutex_);
  return status_;
}
RemovalProgressTracker RemovalSession::progress() const {
  std::lock_guard lk(mutex_);
  return progress_;
}
double RemovalSession::elapsed_s() const {
  std::lock_guard lk(mutex_);
  if (state_ == RemovalState::Idle) return 0.0;
  const auto end = state_ == RemovalState::Running || state_ == RemovalState::Cancelling
                       ? std::chrono::steady_clock::now()
                       : ended_;
  return std::chrono::duration<double>(end - started_).count();
}
std::optional<RemovalReport> RemovalSession::report() const {
  std::lock_guard lk(mutex_);
  return report_;
}
fs::path RemovalSession::run_dir() const {
  std::lock_guard lk(mutex_);
  return run_dir_;
}
std::uint64_t RemovalSession::runs_ended() const {
  std::lock_guard lk(mutex_);
  return runs_ended_;
}

RemovalState RemovalSession::wait(std::chrono::milliseconds timeout) const {
  std::unique_lock lk(mutex_);
  changed_.wait_for(lk, timeout,
                    [&] { return state_ != RemovalState::Running && state_ != RemovalState::Cancelling; });
  return state_;
}

void RemovalSession::finish(RemovalState s, const std::string& status) {
  std::lock_guard lk(mutex_);
  state_ = s;
  status_ = status;
  ended_ = std::chrono::steady_clock::now();
  ++runs_ended_;
  changed_.notify_all();
}

void RemovalSession::work(fs::path run_dir, RemovalOptions options) {
  const BackgroundPriority background;  // the GUI thread goes first
  try {
    {
      // The cost model of the ETA: views, fine-tune length and the optional steps of this run.
      const TrainConfig config = read_run_config(run_dir);
      const Dataset ds = load_dataset(config.data, dataset_options(config));
      const int iters =
          options.finetune_iterations > 0 ? options.finetune_iterations : std::max(100, config.scaled_iteration(4000));
      const bool intrinsic = config.mode == "intrinsic";
      const RemovalCostModel cost = RemovalCostModel::estimate(
          ds.train.size(), iters, intrinsic && !options.ablate.count("lamask"), intrinsic && !options.ablate.count("material"));
      std::lock_guard lk(mutex_);
      const bool frozen = state_ == RemovalState::Cancelling;
      progress_ = RemovalProgressTracker(cost);
      if (frozen) progress_.freeze();
      status_ = "removing in " + run_dir.string();
    }
    const RemovalReport report = run_removal(
        run_dir, options,
        [this](const RemovalProgress& p) {
          std::lock_guard lk(mutex_);
          progress_.update(p, std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
          if (state_ == RemovalState::Running)
            status_ = std::string(removal_step_name(p.step)) + (p.detail.empty() ? "" : ": " + p.detail);
        },
        &stop_);
    {
      std::lock_guard lk(mutex_);
      report_ = report;
    }
    if (report.cancelled || stop_) {
      finish(RemovalState::Cancelled, "cancelled; the run folder is consistent: Remove again resumes");
      return;
    }
    char line[256];
    std::snprintf(line, sizeof line, "done: %zu Gaussians removed, %zu added, %d fine-tune iterations -> %s",
                  report.selected, report.added, report.finetune_iterations, report.out_dir.string().c_str());
    std::string status = line;
    if (!report.finetune_restarted.empty())
      status += " (the fine-tune started over: the earlier one was made from other inputs, changed: " +
                report.finetune_restarted + ")";
    finish(RemovalState::Done, status);
  } catch (const std::exception& e) {
    if (stop_)  // the 2D inpainting stops by throwing
      finish(RemovalState::Cancelled, "cancelled; the run folder is consistent: Remove again resumes");
    else
      finish(RemovalState::Error, e.what());
  }
}

}  // namespace goris::ui
