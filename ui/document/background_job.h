#pragma once
// One piece of work on a worker thread, with the states the editor's jobs share (the capture import, the
// export, the removal and the training):
//
//   Idle --start--> Running --(the work returns)--> Done
//   Running --pause--> Paused --resume--> Running                  (work that calls pause_point only)
//   Running / Paused --cancel--> Cancelling --(the work notices the stop flag)--> Cancelled
//   any failure --> Error
//   Done / Cancelled / Error --start--> Running
//
// The work gets the stop flag, sets the status line as it goes and returns the line that says how it
// ended; it may also end the run as cancelled by throwing JobCancelled with the line to show. How a run whose
// stop flag is up ends is the job's StopRule:
//   - Cancels: however the work ended, the run was cancelled (the status is the cancelled status line);
//   - WorkDecides: the work's own ending stands (training's stop writes a checkpoint and ends in Done; the
//     export throws JobCancelled with what it kept).
// An exception otherwise ends the run in Error, its message the status. The GUI polls state() and status()
// and never waits; Guarded<T> holds what the work hands back to it (progress, results).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

namespace goris::ui {

enum class JobState { Idle, Running, Paused, Cancelling, Done, Cancelled, Error };
const char* job_state_name(JobState s);
inline bool job_active(JobState s) {  // Running, Paused or Cancelling: a run is under way
  return s == JobState::Running || s == JobState::Paused || s == JobState::Cancelling;
}

// Thrown by the work to end its run in Cancelled with this status line.
struct JobCancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class BackgroundJob {
 public:
  using Work = std::function<std::string(const std::atomic<bool>& stop)>;
  enum class StopRule { Cancels, WorkDecides };

  explicit BackgroundJob(std::string name, StopRule rule = StopRule::Cancels) : name_(std::move(name)), rule_(rule) {}
  ~BackgroundJob();  // cancels and joins the worker
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  // Starts `work` on the worker. Throws goris::Error while one runs.
  void start(Work work, const std::string& status = "starting");
  // Running / Paused -> Cancelling, the status saying `status`; otherwise nothing. With nullopt the status
  // line stays the work's (set_status goes on showing).
  void cancel(const std::optional<std::string>& status = std::string("cancelling"));
  void pause();   // Running -> Paused (the work stops at its next pause_point); otherwise nothing
  void resume();  // Paused -> Running; otherwise nothing
  // The worker's status line while it runs or is paused (ignored once a cancel has set its own line).
  void set_status(const std::string& status);
  // The status line of a cancelled run (StopRule::Cancels) when the work ends after the stop.
  void set_cancelled_status(const std::string& status);
  // Worker side, between steps: while the job is paused, shows `paused` and blocks until it is resumed or
  // cancelled; then, if it runs, shows `running`.
  void pause_point(const std::string& paused, const std::string& running);

  JobState state() const;
  bool active() const;  // Running, Paused or Cancelling
  std::string status() const;
  double elapsed_s() const;          // since start (frozen once the job ended)
  std::uint64_t runs_ended() const;  // grows whenever a run ends, however it ended
  // Blocks until no run is active or the timeout passes; returns the state. Tests and shutdown only.
  JobState wait(std::chrono::milliseconds timeout = std::chrono::hours(24)) const;

 private:
  void end(JobState s, const std::string& status);  // the run's end, StopRule applied
  void finish(JobState s, const std::string& status);

  std::string name_;
  StopRule rule_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  JobState state_ = JobState::Idle;
  std::string status_ = "idle", cancelled_status_ = "cancelled";
  bool cancel_line_ = false;  // the cancel set the status line
  std::chrono::steady_clock::time_point started_{}, ended_{};
  std::uint64_t runs_ended_ = 0;
  std::atomic<bool> stop_{false};
  std::thread worker_;
};

// The read side of a BackgroundJob for a class that runs its work on one (the job a member of its own,
// declared last so that it is joined before the members its work uses go): state, status and timing.
class JobReadout {
 public:
  JobState state() const { return job_->state(); }
  bool active() const { return job_->active(); }  // Running, Paused or Cancelling
  // One line: what the worker does, why it failed, or how it ended.
  std::string status() const { return job_->status(); }
  double elapsed_s() const { return job_->elapsed_s(); }          // since start (frozen once the run ended)
  std::uint64_t runs_ended() const { return job_->runs_ended(); }  // grows whenever a run ends
  // Blocks until no run is active or the timeout passes; returns the state. Tests and shutdown only.
  JobState wait(std::chrono::milliseconds timeout = std::chrono::hours(24)) const { return job_->wait(timeout); }

 protected:
  explicit JobReadout(const BackgroundJob& job) : job_(&job) {}  // `job` may be constructed later
  ~JobReadout() = default;

 private:
  const BackgroundJob* job_;
};

// A value the worker hands to the GUI thread (progress, results): copied out and changed under its own lock.
template <class T>
class Guarded {
 public:
  T get() const {
    std::lock_guard lk(mutex_);
    return value_;
  }
  void set(T value) {
    std::lock_guard lk(mutex_);
    value_ = std::move(value);
  }
  // Calls f(value) under the lock and returns what it returns.
  template <class F>
  auto with(F&& f) {
    std::lock_guard lk(mutex_);
    return f(value_);
  }

 private:
  mutable std::mutex mutex_;
  T value_{};
};

}  // namespace goris::ui
