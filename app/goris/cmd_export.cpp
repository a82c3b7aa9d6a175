// `goris export RUN [--ply OUT.ply] [--baked OUT.ply] [--renders DIR [--path test|train|orbit] [--frames N]]
// [--iters N] [--device D]`: the exports of a run folder (RUN or RUN/removal), see render/export/run_export.h.
// Every output path is checked before any work starts; SIGINT, SIGTERM or SIGHUP during the distillation ends
// it early, the baked model so far is still written (marked "stopped" in its json), the exports after it are
// skipped and the command exits 130, 143 or 129.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/goris/command.h"
#include "app/goris/number_checks.h"
#include "app/goris/stop_signals.h"
#include "core/train/run_folder.h"
#include "core/train/run_output_guard.h"
#include "core/util/error.h"
#include "render/export/run_export.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, ply, baked, renders, path = "test", device = "auto";
  int frames = 0, iters = 2000, extra_views = -1;
  float geometry_lr_scale = 0.0f;
  float sh_lr_scale = 20.0f;  // DistillSettings' default
  std::uint64_t seed = 0;
};

void print_baked(const BakedReport& r) {
  const DistillResult& d = r.distill;
  if (!r.distilled)
    std::printf("baked: radiance run, the model is plain SH already: %s is the --ply export without the extra "
                "properties (baked filter check: %.2f dB against the run's renders)\n",
                r.ply.string().c_str(), d.psnr);
  else
    std::printf("baked: %d iterations%s on %zu target views (%zu interpolated) in %.1f s; fidelity on %zu held-out "
                "(%s) views: PSNR %.2f dB against the run's shaded renders (%.2f dB before distillation)\n",
                d.iterations, d.stopped ? " (stopped)" : "", d.target_views, d.extra_views, d.seconds_total,
                d.holdout_views, r.holdout.c_str(), d.psnr, d.psnr_start);
  if (std::isfinite(r.gt_psnr_run))
    std::printf("against the test images: run %.2f dB, baked %.2f dB\n", r.gt_psnr_run, r.gt_psnr_baked);
  std::printf("wrote %s and %s\n", r.ply.string().c_str(), r.json.string().c_str());
}

void run_export(const Options& o) {
  if (o.ply.empty() && o.baked.empty() && o.renders.empty())
    throw Error("goris export", "nothing to export: give at least one of --ply OUT.ply (intrinsic PLY), --baked OUT.ply "
                                "(distilled standard 3DGS PLY), --renders DIR (PNG frames)");
  if (!o.ply.empty() && !o.baked.empty() && fs::absolute(o.ply) == fs::absolute(o.baked))
    throw Error(o.ply, "--ply and --baked name the same file");
  const RenderPath path = parse_render_path(o.path);
  // Fail on a bad path now, not after a distillation: never into the data set or over the run's inputs.
  const fs::path run_dir = fs::absolute(o.run);
  OutputGuard guard;
  try {
    guard = run_output_guard(run_dir, read_run_config(run_dir));
  } catch (const Error&) {
  }  // not a run: RunExport below says so, after the paths' own problems
  if (!o.ply.empty()) check_output_file(o.ply, guard);
  if (!o.baked.empty()) {
    check_output_file(o.baked, guard);
    check_output_file(baked_json_path(o.baked), guard);
  }
  if (!o.renders.empty()) check_output_dir(o.renders, guard);

  const Device device = resolve_device(o.device);
  RunExport ex(o.run, device);
  std::printf("exporting %s (%s run, %zu Gaussians from %s) on %s\n", ex.run_dir().string().c_str(),
              ex.config().mode.c_str(), ex.model().count(), ex.model_source().c_str(), device_name(device));
  std::fflush(stdout);  // before the progress on stderr
  const bool tty = isatty(STDERR_FILENO);

  if (!o.ply.empty()) {
    ex.write_ply(o.ply);
    std::printf("ply: wrote %s (standard 3DGS layout, 3D filter baked in%s)\n", o.ply.c_str(),
                ex.intrinsic() ? ", intrinsic attributes as extra properties" : "");
    std::fflush(stdout);
  }
  if (!o.baked.empty()) {
    DistillSettings s;
    s.iterations = o.iters;
    s.extra_views = o.extra_views;
    s.geometry_lr_scale = o.geometry_lr_scale;
    s.sh_lr_scale = o.sh_lr_scale;
    s.seed = o.seed;
    s.progress_every = tty ? 10 : 100;
    auto progress = [tty](const DistillProgress& p) {
      const bool train = p.phase == "distilling";
      if (!tty && !train && p.done != p.total) return;
      if (train)
        std::fprintf(stderr, "%sdistilling [%d/%d] loss %.4f  PSNR %5.2f dB  %.1f it/s  ETA %.0f s%s", tty ? "\r" : "",
                     p.done, p.total, p.loss, p.psnr, p.it_per_s, p.eta_s, tty ? "   " : "\n");
      else
        std::fprintf(stderr, "%s%s %d/%d%s", tty ? "\r" : "", p.phase.c_str(), p.done, p.total, tty ? "   " : "\n");
      if (tty && p.done == p.total) std::fprintf(stderr, "\n");
    };
    BakedReport r;
    int stopped_by = 0;
    {
      const cli::StopSignals stop;
      r = ex.write_baked(o.baked, s, progress, stop.flag());
      stopped_by = stop.signal();
    }
    print_baked(r);
    if (stopped_by) {
      std::printf("interrupted (%s): the distillation stopped early%s\n", cli::stop_signal_name(stopped_by).c_str(),
                  o.renders.empty() ? "" : "; --renders skipped");
      cli::set_exit_code(128 + stopped_by);
      return;
    }
    std::fflush(stdout);
  }
  if (!o.renders.empty()) {
    const RendersReport r = ex.write_renders(o.renders, path, o.frames, [tty](size_t done, size_t total) {
      if (tty) std::fprintf(stderr, "\rrendering %zu/%zu%s", done, total, done == total ? "\n" : "");
    });
    std::printf("renders: %zu %s frames at %dx%d (%.1f ms each) -> %s, contact sheet %s\n", r.frames.size(),
                render_path_name(path), r.width, r.height, r.ms_per_frame, r.dir.string().c_str(),
                r.contact_sheet.filename().string().c_str());
  }
}

void setup_export(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand(
      "export", "Export a run (RUN or RUN/removal): intrinsic PLY, distilled standard 3DGS PLY, rendered frames");
  c->add_option("run", o->run, "Run folder (goris train) or stage-2 result (RUN/removal)")->required();
  c->add_option("--ply", o->ply,
                "Write the model in the standard 3DGS layout, intrinsic attributes as extra properties, 3D filter "
                "baked into scales and opacities");
  auto* baked = c->add_option("--baked", o->baked,
                "Write a standard SH-only 3DGS model distilled from the run's shaded renders (any viewer shows it), "
                "and OUT.json beside it with the fidelity PSNR on held-out views");
  auto* renders = c->add_option("--renders", o->renders,
                                "Write one PNG per frame from the run's renderer, contact_sheet.png and cameras.json");
  c->add_option("--path", o->path,
                "Cameras for --renders: test (the data set's test views), train, or orbit (a circle around the "
                "scene at the cameras' mean height and distance, looking at where they look)")
      ->check(CLI::IsMember({"test", "train", "orbit"}))
      ->needs(renders);
  c->add_option("--frames", o->frames, "Orbit: number of frames (default 36); test/train: that many evenly spaced views")
      ->check(cli::whole(0, 100000))
      ->needs(renders);
  c->add_option("--iters", o->iters, "Distillation iterations for --baked (default 2000)")
      ->check(cli::whole(1, cli::kIntMax))
      ->needs(baked);
  c->add_option("--extra-views", o->extra_views,
                "Cameras interpolated between training cameras as extra distillation targets (default: as many as "
                "the training cameras)")
      ->check(cli::whole(0, 100000))
      ->needs(baked);
  c->add_option("--geometry-lr", o->geometry_lr_scale,
                "Position/scale/rotation/opacity learning rates during distillation, as a factor of the run's "
                "(default 0: geometry frozen)")
      ->check(cli::real(0, cli::kRealMax))
      ->needs(baked);
  c->add_option("--sh-lr", o->sh_lr_scale, "SH learning rates during distillation, as a factor of the run's (default 20)")
      ->check(cli::real(1e-30, cli::kRealMax))
      ->needs(baked);
  c->add_option("--seed", o->seed, "Seed of the distillation's view order and interpolated cameras")
      ->check(cli::whole(0, cli::kSeedMax))
      ->needs(baked);
  c->add_option("--device", o->device, "auto | cpu | cuda")->check(CLI::IsMember({"auto", "cpu", "cuda"}));
  c->callback([o] { run_export(*o); });
}

}  // namespace
GORIS_COMMAND(60, setup_export);
