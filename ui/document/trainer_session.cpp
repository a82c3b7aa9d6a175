#include "ui/document/trainer_session.h"

#include <algorithm>
#include <cstdio>

#include "core/util/error.h"
#include "train/loop/checkpoint.h"
#include "train/radiance/raster_renderer.h"
#include "train/run/run_folder.h"
#include "train/setup/auto_mode.h"
#include "train/setup/run_renderer.h"
#include "train/setup/training_setup.h"

namespace goris::ui {

namespace fs = std::filesystem;

const char* training_state_name(JobState s) { return s == JobState::Cancelling ? "stopping" : job_state_name(s); }

TrainerSession::~TrainerSession() { stop(); }

void TrainerSession::start(const TrainRequest& request) {
  if (const JobState s = job_.state(); job_active(s))
    throw Error(std::string("training is ") + training_state_name(s) + ": stop it before starting again");
  if (request.iterations <= 0) throw Error("training: the iteration target must be positive");
  if (request.run_dir.empty()) throw Error("training: no run folder given");
  job_.start([this, request](const std::atomic<bool>& stop) { return work(request, stop); });
}

void TrainerSession::publish_snapshot(int iteration) {
  std::shared_ptr<const std::string> renderer_state;
  if (shading_) renderer_state = std::make_shared<const std::string>(renderer_->save_own_state());
  auto snap = std::make_shared<const ModelSnapshot>(trainer_->model(), iteration,
                                                    RasterRenderer::settings_for(trainer_->config()), shading_,
                                                    std::move(renderer_state));
  last_snapshot_iteration_ = iteration;
  last_snapshot_time_ = std::chrono::steady_clock::now();
  snapshot_.with([&](Published& p) {
    p.model = std::move(snap);
    ++p.version;
  });
}

// A new run, or the latest checkpoint of the folder, set up as `goris train` does it
// (train/setup/training_setup.h); the in-memory trainer is reused when the folder is the one trained last.
void TrainerSession::prepare_trainer(const TrainRequest& rq) {
  const fs::path run_dir = fs::absolute(rq.run_dir);
  if (trainer_ && run_dir == run_dir_) {
    const int target = rq.more ? trainer_->state().iteration + rq.iterations : rq.iterations;
    if (trainer_->state().iteration >= target)
      throw Error(run_dir.string(),
                  "already trained for " + std::to_string(trainer_->state().iteration) + " iterations; ask for more");
    if (target != trainer_->config().iterations) {
      // A different target: a new Trainer over the same state and images, as `goris train --resume --iters`.
      TrainConfig config = trainer_->config();
      config.iterations = target;
      std::vector<TrainView> views = trainer_->views();
      const float extent = trainer_->extent();
      TrainerState state = std::move(trainer_->state());
      trainer_.reset();
      trainer_ = std::make_unique<Trainer>(config, std::move(views), extent, renderer_, std::move(state));
    }
    return;
  }
  trainer_.reset();
  run_dir_ = run_dir;
  shown_run_dir_.set(run_dir);
  history_.with([](TrainingHistory& h) { h.clear(); });
  const fs::path data = rq.data.empty() ? fs::path() : fs::weakly_canonical(fs::absolute(rq.data));
  TrainConfig config = rq.config;
  std::optional<ResumePoint> resumed;
  if (latest_checkpoint(run_dir)) {
    job_.set_status("reading the latest checkpoint");
    resumed = read_latest_checkpoint(run_dir);
    config = resumed->checkpoint.config;
    config.device = rq.config.device;  // where to train is this machine's choice, as `goris train --device`
    if (!data.empty() && fs::weakly_canonical(fs::path(config.input.data)) != data)
      throw Error(run_dir.string(), "this run was trained on " + config.input.data + ", not " + data.string());
  } else {
    if (fs::exists(run_config_path(run_dir)))
      throw Error(run_dir.string(),
                  "holds a run (config.json) but no checkpoint to resume from; choose another run folder");
    if (data.empty()) throw Error(run_dir.string(), "no data set to train on");
    config.input.data = data.string();
  }
  const int done = resumed ? resumed->checkpoint.state.iteration : 0;
  config.iterations = rq.more ? done + rq.iterations : rq.iterations;
  // As `goris train --resume`: a run that reached its iterations is finished once its outputs are written
  // after its last checkpoint; one stopped in between is loaded to write them (no iteration runs).
  if (resumed && done >= config.iterations) {
    if (run_outputs_written_after(run_dir, resumed->file, config))
      throw Error(run_dir.string(), "already trained for " + std::to_string(done) + " iterations; ask for more");
    config.iterations = done;
  }
  job_.set_status("loading " + config.input.data);
  PreparedTraining prep = prepare_training(run_dir, config, std::move(resumed), [this](size_t i, size_t n) {
    job_.set_status("loading images " + std::to_string(i + 1) + "/" + std::to_string(n));
  });
  renderer_ = std::move(prep.renderer);
  trainer_ = std::move(prep.trainer);
  // Snapshots of an intrinsic run carry what the display shades them with.
  shading_.reset();
  if (as_intrinsic(renderer_.get()))
    shading_ = std::make_shared<const ShadingSource>(ShadingSource{trainer_->config(), prep.extent});
}

void TrainerSession::on_progress(const TrainProgress& p) {
  const auto now = std::chrono::steady_clock::now();
  progress_.set(p);
  history_.with([&](TrainingHistory& h) {
    h.add({p.iteration, float(p.loss), float(p.psnr), float(p.gaussians), float(p.it_per_s)});
  });
  const bool due = p.iteration - last_snapshot_iteration_ >= options_.snapshot_every ||
                   std::chrono::duration<double>(now - last_snapshot_time_).count() >= options_.snapshot_interval_s;
  if (due && p.iteration != last_snapshot_iteration_) publish_snapshot(p.iteration);
  job_.pause_point("paused at iteration " + std::to_string(p.iteration), "training");
}

// Under the job's StopRule::WorkDecides: a stop ends the loop at the next iteration with a checkpoint, and
// the run is Done.
std::string TrainerSession::work(const TrainRequest& rq, const std::atomic<bool>& stop) {
  try {
    prepare_trainer(rq);
    write_run_config(run_dir_, trainer_->config());
    progress_.set(trainer_->progress(0));
    job_.set_status("training");
    publish_snapshot(trainer_->state().iteration);

    Trainer::RunOptions ro;
    ro.run_dir = run_dir_;
    ro.stop = &stop;
    ro.progress_every = 1;
    ro.on_progress = [this](const TrainProgress& p) { on_progress(p); };
    ro.before_step = [this](Trainer& t) {  // --mode auto's decision after the warm-up may switch the renderer
      if (const auto d = apply_auto_mode(t, run_dir_)) {
        renderer_ = t.renderer();
        if (as_intrinsic(renderer_.get()))
          shading_ = std::make_shared<const ShadingSource>(ShadingSource{t.config(), t.extent()});
        job_.set_status(d->message());
      }
    };
    const Trainer::RunResult result = trainer_->run(ro);
    const TrainerState& st = trainer_->state();
    if (st.iteration != last_snapshot_iteration_) publish_snapshot(st.iteration);
    if (result == Trainer::RunResult::Stopped)
      return "stopped at iteration " + std::to_string(st.iteration) + "; checkpoint " +
             checkpoint_path(run_dir_, st.iteration).filename().string();
    write_trained_run(run_dir_, *trainer_, *renderer_);
    char line[160];
    std::snprintf(line, sizeof line, "done: %d iterations, %zu Gaussians, PSNR %.2f dB", st.iteration, st.model.count(),
                  st.ema_psnr);
    return line;
  } catch (...) {
    trainer_.reset();  // a failed run is reloaded from its checkpoints by the next start
    throw;
  }
}

}  // namespace goris::ui
