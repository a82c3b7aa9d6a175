#pragma once
// Stage 2 (object removal, render/removal/removal_pipeline.h run_removal) on its own thread for the editor,
// on the same run folder as `goris remove`. States:
//
//   Idle --start--> Running --(all steps done)--> Done
//   Running --cancel--> Cancelling --(the pipeline stops)--> Cancelled     any failure --> Error
//   Done / Cancelled / Error --start--> Running (a new run resumes from what RUN/removal holds)
//
// The GUI polls progress() (per step, overall, ETA) and never waits. Cancelling raises the pipeline's stop
// flag: it leaves the run folder consistent (finished steps' files, the fine-tune's checkpoint) and a later
// start resumes.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "render/removal/removal_pipeline.h"
#include "ui/removal_progress.h"

namespace goris::ui {

enum class RemovalState { Idle, Running, Cancelling, Done, Cancelled, Error };
const char* removal_state_name(RemovalState s);

class RemovalSession {
 public:
  RemovalSession() = default;
  ~RemovalSession();  // cancels and joins the worker
  RemovalSession(const RemovalSession&) = delete;
  RemovalSession& operator=(const RemovalSession&) = delete;

  // Starts run_removal(run_dir, options) on the worker. Throws goris::Error while one runs.
  void start(const std::filesystem::path& run_dir, const RemovalOptions& options);
  void cancel();  // Running -> Cancelling; otherwise nothing

  RemovalState state() const;
  bool active() const;  // Running or Cancelling
  // One line: what the worker does, why it failed, or how it ended.
  std::string status() const;
  RemovalProgressTracker progress() const;
  double elapsed_s() const;  // since start (frozen when the run ended)
  std::optional<RemovalReport> report() const;  // of the last run that returned (finished or cancelled)
  std::filesystem::path run_dir() const;
  std::uint64_t runs_ended() const;  // grows whenever a run ends, however it ended

  // Blocks until no run is active or the timeout passes; returns the state. Tests and shutdown only.
  RemovalState wait(std::chrono::milliseconds timeout = std::chrono::hours(24)) const;

 private:
  void work(std::filesystem::path run_dir, RemovalOptions options);
  void finish(RemovalState s, const std::string& status);

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  RemovalState state_ = RemovalState::Idle;
  std::string status_ = "idle";
  RemovalProgressTracker progress_;
  std::optional<RemovalReport> report_;
  std::filesystem::path run_dir_;
  std::chrono::steady_clock::time_point started_{}, ended_{};
  std::uint64_t runs_ended_ = 0;
  std::atomic<bool> stop_{false};
  std::thread worker_;
};

}  // namespace goris::ui
