#pragma once
// Stage-1 training on its own thread for the editor (docs/design/architecture.md, The editor), set up as
// `goris train` does (train/setup/training_setup.h: modes radiance / intrinsic / auto, normal priors,
// make_renderer) with the same run folder (config.json, checkpoints/, log.csv, point_cloud.ply,
// environment.png; an existing run is resumed from its latest checkpoint). It runs on a background job
// (ui/document/background_job.h) whose stop is a finish, not a cancel:
//
//   Idle --start--> Running --pause--> Paused --resume--> Running
//   Running/Paused --stop--> Cancelling ("stopping") --(checkpoint written)--> Done
//   Running --(target iteration reached)--> Done          any failure --> Error
//   Done/Error --start--> Running (continues the same run, e.g. with a larger iteration target)
//
// The GUI thread only calls the non-blocking members; the worker publishes progress, a bounded history
// for plots, and model snapshots (every `snapshot_every` iterations or `snapshot_interval_s` seconds,
// whichever comes first, and at the end); an intrinsic run's snapshots carry the renderer's own state
// (environment map, roughness net) so the display shades with the current environment. Nothing here knows
// about windows or OpenGL.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "train/config/train_config.h"
#include "train/loop/trainer.h"
#include "ui/document/background_job.h"
#include "ui/display/model_snapshot.h"
#include "ui/document/training_history.h"

namespace goris::ui {

// The job's state as the training shows it: a cancel is a stop ("stopping").
const char* training_state_name(JobState s);

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

class TrainerSession : public JobReadout {
 public:
  explicit TrainerSession(SessionOptions options = {}) : JobReadout(job_), options_(options) {}
  ~TrainerSession();  // stops (writing a checkpoint) and joins the worker
  TrainerSession(const TrainerSession&) = delete;
  TrainerSession& operator=(const TrainerSession&) = delete;

  // Starts the worker. Allowed in Idle, Done and Error (throws goris::Error otherwise). A request for the
  // run folder already in memory continues that trainer; another folder is loaded (new or resumed).
  void start(const TrainRequest& request);
  void pause() { job_.pause(); }    // Running -> Paused (the iteration in flight completes first); otherwise nothing
  void resume() { job_.resume(); }  // Paused -> Running; otherwise nothing
  // Running/Paused -> Cancelling (stopping) -> Done, with a checkpoint; otherwise nothing.
  void stop() { job_.cancel(std::nullopt); }
  // state(), status(), wait() (JobReadout): the worker's; training_state_name() names a stop "stopping".

  TrainProgress progress() const { return progress_.get(); }
  TrainingHistory history() const { return history_.get(); }
  std::shared_ptr<const ModelSnapshot> snapshot() const { return snapshot_.get().model; }
  std::uint64_t snapshot_version() const { return snapshot_.get().version; }  // grows with every new snapshot
  std::filesystem::path run_dir() const { return shown_run_dir_.get(); }

 private:
  struct Published {
    std::shared_ptr<const ModelSnapshot> model;
    std::uint64_t version = 0;
  };
  std::string work(const TrainRequest& request, const std::atomic<bool>& stop);
  void prepare_trainer(const TrainRequest& request);  // worker thread
  void on_progress(const TrainProgress& p);           // worker thread, between iterations
  void publish_snapshot(int iteration);

  SessionOptions options_;
  Guarded<TrainProgress> progress_;
  Guarded<TrainingHistory> history_;
  Guarded<Published> snapshot_;
  Guarded<std::filesystem::path> shown_run_dir_;  // run_dir_ for the GUI thread

  // Owned by the worker while it runs; by start() between runs.
  std::unique_ptr<Trainer> trainer_;
  std::shared_ptr<DifferentiableRenderer> renderer_;
  std::shared_ptr<const ShadingSource> shading_;  // intrinsic runs only
  std::filesystem::path run_dir_;
  int last_snapshot_iteration_ = 0;
  std::chrono::steady_clock::time_point last_snapshot_time_;
  BackgroundJob job_{"training", BackgroundJob::StopRule::WorkDecides};  // last: joined before the members it uses go
};

}  // namespace goris::ui
