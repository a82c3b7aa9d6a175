#pragma once
// Stage-1 training on its own thread for the editor (docs/design/architecture.md, The editor), set up as
// `goris train` does (render/train/training_setup.h: modes radiance / intrinsic / auto, normal priors,
// make_renderer) with the same run folder (config.json, checkpoints/, log.csv, point_cloud.ply,
// environment.png; an existing run is resumed from its latest checkpoint). A small state machine:
//
//   Idle --start--> Running --pause--> Paused --resume--> Running
//   Running/Paused --stop--> Stopping --(checkpoint written)--> Done
//   Running --(target iteration reached)--> Done          any failure --> Error
//   Done/Error --start--> Running (continues the same run, e.g. with a larger iteration target)
//
// The GUI thread only calls the non-blocking members; the worker publishes progress, a bounded history
// for plots, and model snapshots (every `snapshot_every` iterations or `snapshot_interval_s` seconds,
// whichever comes first, and at the end); an intrinsic run's snapshots carry the renderer's own state
// (environment map, roughness net) so the display shades with the current environment. Nothing here knows
// about windows or OpenGL.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "core/train/train_config.h"
#include "core/train/trainer.h"
#include "ui/model_snapshot.h"
#include "ui/training_history.h"

namespace goris::ui {

enum class SessionState { Idle, Running, Paused, Stopping, Done, Error };
const char* state_name(SessionState s);

struct TrainRequest {
  std::filesystem::path data;     // the data set (must be the run's own when the run folder already holds one)
  std::filesystem::path run_dir;  // the run folder: created, or resumed when it holds a checkpoint
  TrainConfig config;             // settings of a new run; a resumed run keeps its own, bar `iterations` and `device`
  int iterations = 0;             // train until this many iterations in total ...
  bool more = false;              // ... or this many more than the run has done (a resumed run: its checkpoint)
};

struct SessionOptions {
  int snapshot_every = 50;           // iterations between model snapshots ...
  double snapshot_interval_s = 0.2;  // ... or seconds, whichever comes first
};

class TrainerSession {
 public:
  explicit TrainerSession(SessionOptions options = {});
  ~TrainerSession();  // stops (writing a checkpoint) and joins the worker
  TrainerSession(const TrainerSession&) = delete;
  TrainerSession& operator=(const TrainerSession&) = delete;

  // Starts the worker. Allowed in Idle, Done and Error (throws goris::Error otherwise). A request for the
  // run folder already in memory continues that trainer; another folder is loaded (new or resumed).
  void start(const TrainRequest& request);
  void pause();   // Running -> Paused (the iteration in flight completes first); otherwise nothing
  void resume();  // Paused -> Running; otherwise nothing
  void stop();    // Running/Paused -> Stopping -> Done, with a checkpoint; otherwise nothing

  SessionState state() const;
  // One line for the status bar: what the worker does, why it failed, or how it ended.
  std::string status() const;
  TrainProgress progress() const;
  TrainingHistory history() const;
  std::shared_ptr<const ModelSnapshot> snapshot() const;
  std::uint64_t snapshot_version() const;  // grows with every new snapshot
  std::filesystem::path run_dir() const;

  // Blocks until the worker is not running (Idle, Done or Error) or the timeout passes; returns the
  // state. For tests and shutdown only: the GUI polls state() instead.
  SessionState wait(std::chrono::milliseconds timeout = std::chrono::hours(24)) const;

 private:
  void work(TrainRequest request);
  void prepare_trainer(const TrainRequest& request);  // worker thread
  void on_progress(const TrainProgress& p);           // worker thread, between iterations
  void publish_snapshot(int iteration);
  void set_status(const std::string& s);
  void finish(SessionState s, const std::string& status);

  SessionOptions options_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  SessionState state_ = SessionState::Idle;
  std::string status_ = "idle";
  TrainProgress progress_;
  TrainingHistory history_;
  std::shared_ptr<const ModelSnapshot> snapshot_;
  std::uint64_t snapshot_version_ = 0;
  bool pause_requested_ = false;
  std::atomic<bool> stop_flag_{false};

  // Owned by the worker while it runs; by start() between runs.
  std::unique_ptr<Trainer> trainer_;
  std::shared_ptr<DifferentiableRenderer> renderer_;
  std::shared_ptr<const ShadingSource> shading_;  // intrinsic runs only
  std::filesystem::path run_dir_;
  int last_snapshot_iteration_ = 0;
  std::chrono::steady_clock::time_point last_snapshot_time_;
  std::thread worker_;
};

}  // namespace goris::ui
