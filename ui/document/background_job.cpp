#include "ui/document/background_job.h"

#include <exception>

#include "core/util/error.h"
#include "ui/display/background_priority.h"

namespace goris::ui {

const char* job_state_name(JobState s) {
  switch (s) {
    case JobState::Idle:
      return "idle";
    case JobState::Running:
      return "running";
    case JobState::Paused:
      return "paused";
    case JobState::Cancelling:
      return "cancelling";
    case JobState::Done:
      return "done";
    case JobState::Cancelled:
      return "cancelled";
    case JobState::Error:
      return "error";
  }
  return "?";
}

BackgroundJob::~BackgroundJob() {
  cancel();
  if (worker_.joinable()) worker_.join();
}

void BackgroundJob::start(Work work, const std::string& status) {
  {
    std::lock_guard lk(mutex_);
    if (job_active(state_))
      throw Error(name_ + ": one is " + job_state_name(state_) + ": wait for it or cancel it first");
  }
  if (worker_.joinable()) worker_.join();  // it has ended: joining does not wait
  std::lock_guard lk(mutex_);
  state_ = JobState::Running;
  status_ = status;
  cancelled_status_ = "cancelled";
  cancel_line_ = false;
  stop_ = false;
  started_ = std::chrono::steady_clock::now();
  worker_ = std::thread([this, work = std::move(work)] {
    const BackgroundPriority priority;
    try {
      end(JobState::Done, work(stop_));
    } catch (const JobCancelled& e) {
      finish(JobState::Cancelled, e.what());
    } catch (const std::exception& e) {
      end(JobState::Error, e.what());
    }
  });
}

void BackgroundJob::end(JobState s, const std::string& status) {
  // Under StopRule::Cancels, once the stop flag is up, however the work ended, the run was cancelled.
  if (rule_ == StopRule::WorkDecides || !stop_) return finish(s, status);
  std::string line;
  {
    std::lock_guard lk(mutex_);
    line = cancelled_status_;
  }
  finish(JobState::Cancelled, line);
}

void BackgroundJob::cancel(const std::optional<std::string>& status) {
  std::lock_guard lk(mutex_);
  if (state_ != JobState::Running && state_ != JobState::Paused) return;
  stop_ = true;
  state_ = JobState::Cancelling;
  if (status) status_ = *status;
  cancel_line_ = status.has_value();
  changed_.notify_all();
}

void BackgroundJob::pause() {
  std::lock_guard lk(mutex_);
  if (state_ != JobState::Running) return;
  state_ = JobState::Paused;
  changed_.notify_all();
}

void BackgroundJob::resume() {
  std::lock_guard lk(mutex_);
  if (state_ != JobState::Paused) return;
  state_ = JobState::Running;
  changed_.notify_all();
}

void BackgroundJob::pause_point(const std::string& paused, const std::string& running) {
  std::unique_lock lk(mutex_);
  if (state_ == JobState::Paused) {
    status_ = paused;
    changed_.wait(lk, [&] { return state_ != JobState::Paused; });
  }
  if (state_ == JobState::Running) status_ = running;
}

void BackgroundJob::set_status(const std::string& status) {
  std::lock_guard lk(mutex_);
  if (state_ == JobState::Running || state_ == JobState::Paused || (state_ == JobState::Cancelling && !cancel_line_))
    status_ = status;
}

void BackgroundJob::set_cancelled_status(const std::string& status) {
  std::lock_guard lk(mutex_);
  cancelled_status_ = status;
}

JobState BackgroundJob::state() const {
  std::lock_guard lk(mutex_);
  return state_;
}

bool BackgroundJob::active() const { return job_active(state()); }

std::string BackgroundJob::status() const {
  std::lock_guard lk(mutex_);
  return status_;
}

double BackgroundJob::elapsed_s() const {
  std::lock_guard lk(mutex_);
  if (state_ == JobState::Idle) return 0.0;
  const auto end = job_active(state_) ? std::chrono::steady_clock::now() : ended_;
  return std::chrono::duration<double>(end - started_).count();
}

std::uint64_t BackgroundJob::runs_ended() const {
  std::lock_guard lk(mutex_);
  return runs_ended_;
}

JobState BackgroundJob::wait(std::chrono::milliseconds timeout) const {
  std::unique_lock lk(mutex_);
  changed_.wait_for(lk, timeout, [&] { return !job_active(state_); });
  return state_;
}

void BackgroundJob::finish(JobState s, const std::string& status) {
  std::lock_guard lk(mutex_);
  state_ = s;
  status_ = status;
  ended_ = std::chrono::steady_clock::now();
  ++runs_ended_;
  changed_.notify_all();
}

}  // namespace goris::ui
