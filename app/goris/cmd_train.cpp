// `goris train DATA --out RUN`: stage-1 training (--mode auto by default: intrinsic for a glossy scene,
// radiance otherwise) into a run folder: config.json, checkpoints/, log.csv and the final point_cloud.ply.
// SIGINT (Ctrl-C), SIGTERM or SIGHUP finishes the current iteration, writes a checkpoint, prints the command
// that resumes the run and exits 130, 143 or 129
// (stop_signals.h), so that `goris train ... && next` does not go on with an unfinished run.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "app/cli_common/stop_signals.h"
#include "core/compute/device.h"
#include "core/io/file_bytes.h"
#include "core/io/output_path.h"
#include "train/loop/checkpoint.h"
#include "train/config/config_presets.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/loop/trainer.h"
#include "core/compute/bench.h"
#include "core/util/duration_text.h"
#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/setup/auto_mode.h"
#include "train/setup/run_renderer.h"
#include "train/setup/training_setup.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string data, out, device = "auto", normals, init;
  std::optional<std::string> mode;  // the configuration's (auto) when not given
  std::optional<int> iters, resolution, init_points, checkpoint_every;
  std::optional<float> downscale;
  std::optional<std::uint64_t> seed;
  std::vector<std::string> sets;  // KEY=VALUE overrides of config.json keys
  std::string preset;             // a preset's name or file (train/config/config_presets.h), applied before `sets`
  bool resume = false, restart = false;
};

std::string shell_quote(const std::string& s) {
  if (s.find_first_of(" \t'\"$\\") == std::string::npos) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The settings the options ask for, applied to `config`: a new run's, or a copy of a resumed run's to
// compare with it. --iters, --checkpoint-every and --device may change on resume and are applied later.
void apply_settings(const Options& o, TrainConfig& config) {
  if (o.mode) config.mode = *enum_from_name<TrainMode>(*o.mode);  // a name, checked by the option
  if (!o.normals.empty()) config.intrinsic.normals = fs::weakly_canonical(fs::absolute(o.normals)).string();
  if (o.seed) config.seed = *o.seed;
  if (o.resolution) config.input.resolution = *o.resolution;
  if (o.downscale) config.input.downscale = *o.downscale;
  if (o.init_points) config.init.random_points = *o.init_points;
  if (!o.init.empty()) {  // read by prepare_training; a missing file fails now, before the images load
    const fs::path init = fs::weakly_canonical(fs::absolute(o.init));
    if (const std::string problem = regular_file_problem(init, "model file"); !problem.empty())
      throw Error(init.string(), "--init: " + problem);  // missing, a folder, a FIFO (never opened), ...
    config.init.model = init.string();
  }
  if (!o.preset.empty()) apply_config_preset(load_config_preset(o.preset), config);
  apply_config_overrides(o.sets, config);
}

// A resumed run keeps its settings: options that would change one are refused, naming the setting with the
// run's value and the asked one; options that repeat the run's values are accepted.
void reject_changes_on_resume(const Options& o, const fs::path& run_dir, const TrainConfig& run) {
  TrainConfig asked = run;
  apply_settings(o, asked);
  const nlohmann::json before = run, after = asked;
  std::string changed;
  for (auto it = after.begin(); it != after.end(); ++it)
    if (before.value(it.key(), nlohmann::json()) != it.value())
      changed += (changed.empty() ? "" : ", ") + it.key() + " " + before.value(it.key(), nlohmann::json()).dump() +
                 " -> " + it.value().dump();
  if (!changed.empty())
    throw Error(run_dir.string(), "settings cannot change when resuming (the run keeps its settings): " + changed +
                "; drop those options, or start the run over with --restart");
}

// --restart: the files of an earlier training run in `run_dir` go, so that nothing of it is resumed or read.
void remove_training_run(const fs::path& run_dir) {
  std::error_code ec;
  fs::remove_all(run_dir / "checkpoints", ec);
  // densify_stop.json: the record of a removed setting that older versions wrote.
  for (const fs::path& f : {run_config_path(run_dir), run_ply_path(run_dir), run_dir / "log.csv", run_dir / "densify_stop.json"})
    fs::remove(f, ec);
}

void run_train(const Options& o) {
  // Stop signals from the start: one that comes while the data loads stops the run at its first step with a
  // checkpoint (resumable), instead of killing it between writing config.json and its first checkpoint.
  const cli::StopSignals stop;
  const fs::path run_dir = fs::absolute(o.out);
  const fs::path data = fs::weakly_canonical(fs::absolute(o.data));
  std::optional<ResumePoint> resumed;
  TrainConfig config;
  if (o.resume) {
    std::error_code ec;
    if (!fs::is_directory(run_dir, ec))
      throw Error(run_dir.string(), fs::exists(run_dir, ec) ? "--resume: is not a folder, so not a run to resume"
                                                            : "--resume: the run folder does not exist (drop --resume "
                                                              "to start a new run there)");
    resumed = read_latest_checkpoint(run_dir);
    if (!resumed)
      throw Error(run_dir.string(), fs::exists(run_config_path(run_dir))
                                        ? "no checkpoint in checkpoints/ to resume from (the run stopped before its "
                                          "first one): start it over with --restart instead of --resume"
                                        : "no checkpoint in checkpoints/ to resume from");
    config = resumed->checkpoint.config;
    reject_changes_on_resume(o, run_dir, config);
    // DATA may be the run's data set at a new folder: checked to hold the same views (train/run/run_data.h).
    use_run_data(run_dir, config, data.string(), "DATA");
    std::printf("resuming %s from iteration %d (%s)\n", run_dir.string().c_str(), resumed->checkpoint.state.iteration,
                resumed->file.filename().string().c_str());
  } else {
    if (o.restart) {
      remove_training_run(run_dir);
    } else if (latest_checkpoint(run_dir)) {
      throw Error(run_dir.string(), "already holds a training run: add --resume to continue it, --restart to start it "
                                    "over, or choose another --out");
    } else if (fs::exists(run_config_path(run_dir))) {
      throw Error(run_dir.string(), "holds a training run that stopped before its first checkpoint (config.json, no "
                                    "checkpoints/): add --restart to start it over, or choose another --out");
    }
    config.input.data = data.string();
    apply_settings(o, config);
  }
  // Never a run inside the data set (or any data set); only the run folder itself is created, and removed
  // again if the run fails before writing anything.
  const RemoveIfLeftEmpty created(run_dir);
  check_output_dir(run_dir, OutputGuard{{data}, {}});
  if (o.iters) config.iterations = *o.iters;
  if (o.checkpoint_every) config.bookkeeping.checkpoint_interval = *o.checkpoint_every;
  config.device = enum_from_name<DeviceChoice>(o.device).value();  // --device's check accepts only the names
  config.validate("training options");
  // A run that reached its last iteration is finished once its outputs are written after that checkpoint:
  // then there is nothing to do. One killed in between (the checkpoint saved, the model not yet) is resumed
  // to write them.
  if (resumed && resumed->checkpoint.state.iteration >= config.iterations) {
    const int done = resumed->checkpoint.state.iteration;
    if (run_outputs_written_after(run_dir, resumed->file, config)) {
      std::printf("already trained for %d iterations: nothing to do (pass a larger --iters to train further)\n", done);
      return;
    }
    std::printf("the run reached iteration %d but stopped before writing its model: writing it\n", done);
  }

  // The shared set-up (train/setup/training_setup.h, also the editor's): data, auto mode, images, state,
  // renderer, trainer. The line before it says the command has started (a large data set loads for a while).
  std::printf("loading %s\n", data.string().c_str());
  std::fflush(stdout);
  PreparedTraining prep = prepare_training(run_dir, config, std::move(resumed), [](size_t i, size_t n) {
    if (isatty(STDERR_FILENO)) std::fprintf(stderr, "\rloading images %zu/%zu", i + 1, n);
  });
  if (isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
  config = prep.config;
  for (const auto& w : prep.dataset.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!prep.auto_mode_reason.empty())
    std::printf("--mode auto: %s (%s)\n", enum_name(config.mode), prep.auto_mode_reason.c_str());
  Trainer& trainer = *prep.trainer;
  const std::vector<TrainView>& views = trainer.views();
  if (config.mode == TrainMode::Intrinsic)
    std::printf("intrinsic mode: %zu/%zu views with glossy masks, %zu with object masks, normal prior %s; shading "
                "from iteration %d\n",
                prep.glossy_views, views.size(), prep.mask_views,
                config.intrinsic.normals.empty() ? "none" : config.intrinsic.normals.c_str(),
                config.shading_from() + 1);
  if (config.intrinsic.env_radius > 0) {
    const glm::vec3& c = config.intrinsic.env_center;
    std::printf("environment on a sphere of radius %.3g around (%.3g, %.3g, %.3g)\n", double(config.intrinsic.env_radius),
                double(c.x), double(c.y), double(c.z));
  }
  if (!prep.initial_model.empty()) std::printf("initial model: %s\n", prep.initial_model.c_str());
  write_run_config(run_dir, config);
  std::printf("training %s (%s, %zu views at %dx%d, extent %.3g) on %s for %d iterations -> %s\n", data.string().c_str(),
              prep.dataset.format.c_str(), views.size(), views[0].camera.width, views[0].camera.height,
              double(prep.extent), device_name(trainer.device()), config.iterations, run_dir.string().c_str());

  const bool tty = isatty(STDERR_FILENO);
  Trainer::RunOptions ro;
  ro.run_dir = run_dir;
  ro.progress_every = tty ? 10 : config.bookkeeping.log_interval;
  ro.before_step = [&](Trainer& t) {  // --mode auto's decision after the warm-up
    if (const auto d = apply_auto_mode(t, run_dir)) {
      std::printf("%s%s\n", tty ? "\n" : "", d->message().c_str());
      std::fflush(stdout);
    }
  };
  ro.on_progress = [tty](const TrainProgress& p) {
    std::fprintf(stderr, "%s[%*d/%d] loss %.4f  PSNR %5.2f dB  %zu Gaussians  %.1f it/s  ETA %s%s", tty ? "\r" : "",
                 int(std::to_string(p.total).size()), p.iteration, p.total, p.loss, p.psnr, p.gaussians, p.it_per_s,
                 duration_text(p.eta_s).c_str(), tty ? "   " : "\n");
    std::fflush(stderr);
  };
  Trainer::RunResult result;
  ro.stop = stop.flag();
  try {
    result = trainer.run(ro);
  } catch (...) {
    if (tty) std::fprintf(stderr, "\n");
    throw;
  }
  if (tty) std::fprintf(stderr, "\n");

  const TrainerState& st = trainer.state();
  if (result == Trainer::RunResult::Stopped) {
    std::printf("interrupted (%s) at iteration %d/%d; checkpoint %s\nresume with: goris train %s --out %s --resume\n",
                cli::stop_signal_name(stop.signal()).c_str(), st.iteration, config.iterations,
                checkpoint_path(run_dir, st.iteration).string().c_str(), shell_quote(data.string()).c_str(),
                shell_quote(run_dir.string()).c_str());
    cli::set_exit_code(stop.exit_code());
    return;
  }
  write_trained_run(run_dir, trainer, *trainer.renderer());
  std::printf("done: %d iterations in %s, %zu Gaussians, training PSNR %.2f dB (smoothed), peak memory %s\n"
              "model: %s\n",
              st.iteration, duration_text(st.elapsed_s).c_str(), st.model.count(), st.ema_psnr, peak_memory_text().c_str(),
              run_ply_path(run_dir).string().c_str());
  if (const IntrinsicRenderer* ir = as_intrinsic(trainer.renderer().get()); ir && ir->ray_totals().frames > 0) {
    const IntrinsicRayTotals& r = ir->ray_totals();
    std::printf("reflection rays: %.0f of %.0f glossy pixels traced per shaded frame (%.1f %% saved by coarse "
                "tracing)\n", double(r.traced) / double(r.frames), double(r.glossy) / double(r.frames),
                100.0 * r.saved_fraction());
  }
}

void setup_train(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("train", "Train a Gaussian scene on a data set into a run folder");
  c->add_option("data", o->data, "Data set folder (NeRF-synthetic, instant-ngp, COLMAP, LLFF)")->required();
  c->add_option("--out", o->out, "Run folder (config.json, checkpoints/, log.csv, point_cloud.ply)")->required();
  c->add_option("--mode", o->mode,
                 "What to train: radiance (SH colour), intrinsic (materials, tracing, shading: stage 1), auto "
                 "(intrinsic only for a glossy scene: from its glossy masks, or detected from the photos after the "
                 "warm-up when it has none)")
      ->check(CLI::IsMember(cli::enum_name_list<TrainMode>()));
  c->add_option("--normals", o->normals, "Folder of normal-prior maps for intrinsic mode (see README)");
  c->add_option("--iters", o->iters, "Number of iterations (default 30000)")->check(cli::whole(1, cli::kIntMax));
  auto* res = c->add_option("--resolution", o->resolution, "Train at this image width (height keeps the aspect)")
                  ->check(cli::whole(1, 65536));
  auto* ds = c->add_option("--downscale", o->downscale, "Divide the image size by this factor (>= 1)")
                 ->check(cli::real(1, 1000));
  res->excludes(ds);
  cli::add_device_option(*c, o->device);
  auto* resume = c->add_flag("--resume", o->resume, "Continue the run in --out from its latest checkpoint");
  c->add_flag("--restart", o->restart,
              "Start the run in --out over: its config.json, checkpoints/, log.csv and point_cloud.ply are removed")
      ->excludes(resume);
  c->add_option("--seed", o->seed, "Random seed (initial points, view order, splits)")->check(cli::whole(0, cli::kSeedMax));
  c->add_option("--init-points", o->init_points, "Random initial points when the data has no SfM points (100000)")
      ->check(cli::whole(1, kMaxRandomInitPoints));
  c->add_option("--init", o->init,
                "Start from this model file (.ply, .compressed.ply, .spz, .splat, .glb) in the data set's frame, "
                "instead of the SfM or random points");
  c->add_option("--checkpoint-every", o->checkpoint_every, "Checkpoint interval in iterations (2000; 0 = end only)")
      ->check(cli::whole(0, cli::kIntMax));
  std::string presets;
  for (const std::string& n : config_preset_names()) presets += (presets.empty() ? "" : ", ") + n;
  c->add_option("--preset", o->preset,
                "Settings applied before --set: a preset's name (" + (presets.empty() ? "none found" : presets) +
                "; `goris config --presets` describes them) or the path of a preset file (resources/presets/*.json)");
  c->add_option("--set", o->sets, "Override any training setting: KEY=VALUE with a config.json key (repeatable)");
  c->callback([o] { run_train(*o); });
}

}  // namespace
GORIS_COMMAND(20, setup_train);
