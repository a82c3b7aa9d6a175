#pragma once
// One piece of work on a worker thread, with the states the editor's jobs share:
//
//   Idle --start--> Running --(the work returns)--> Done
//   Running --cancel--> Cancelling --(the work notices the stop flag)--> Cancelled    a failure --> Error
//   Done / Cancelled / Error --start--> Running
//
// The work gets the stop flag, sets the status line as it goes and returns the line that says how it
// ended; an exception ends it in Error (its message the status), or in Cancelled once the stop flag is up.
// The GUI polls state() and status() and never waits. Used by the capture import (ui/capture_job.h).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace goris::ui {

enum class JobState { Idle, Running, Cancelling, Done, Cancelled, Error };
const char* job_state_name(JobState s);

class BackgroundJob {
 public:
  using Work = std::function<std::string(const std::atomic<bool>& stop)>;

  explicit BackgroundJob(std::string name) : name_(std::move(name)) {}
  ~BackgroundJob();  // cancels and joins the worker
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  // Starts `work` on the worker. Throws goris::Error while one runs.
  void start(Work work, const std::string& status = "starting");
  // Running -> Cancelling (the status says `status`); otherwise nothing.
  void cancel(const std::string& status = "cancelling");
  // The worker's status line while it runs (ignored once cancelling).
  void set_status(const std::string& status);
  // The status line of a cancelled run when the work ends by an exception after the stop.
  void set_cancelled_status(const std::string& status);

  JobState state() const;
  bool active() const;  // Running or Cancelling
  std::string status() const;
  double elapsed_s() const;          // since start (frozen once the job ended)
  std::uint64_t runs_ended() const;  // grows whenever a run ends, however it ended
  // Blocks until no run is active or the timeout passes; returns the state. Tests and shutdown only.
  JobState wait(std::chrono::milliseconds timeout = std::chrono::hours(24)) const;

 private:
  void finish(JobState s, const std::string& status);

  std::string name_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  JobState state_ = JobState::Idle;
  std::string status_ = "idle", cancelled_status_ = "cancelled";
  std::chrono::steady_clock::time_point started_{}, ended_{};
  std::uint64_t runs_ended_ = 0;
  std::atomic<bool> stop_{false};
  std::thread worker_;
};

}  // namespace goris::ui
