// `goris remove RUN [--inpainter NAME | --inpainted DIR] [--ablate material|lamask] [--iters N]`: stage 2 on a
// trained run (removal/pipeline/removal_pipeline.h): each step with its progress, every intermediate in
// RUN/removal/, the cleaned scene as the run folder RUN/removal (render / eval / export take it). SIGINT,
// SIGTERM or SIGHUP stops at the next safe point with exit status 130, 143 or 129; running the command
// again resumes.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "app/cli_common/stop_signals.h"
#include "core/compute/device.h"
#include "core/util/error.h"
#include "core/util/number_text.h"
#include "removal/pipeline/removal_ablations.h"
#include "removal/pipeline/removal_pipeline.h"

namespace {
using namespace goris;

struct Options {
  std::string run, inpainter = RemovalOptions{}.inpainter, inpainted, device = "auto", lighting_fresnel = "relative",
              lighting_targets = "dereflect", data, fill_truth;
  std::vector<std::string> ablate;
  int iters = 0;
  double view_fill = RemovalOptions{}.view_fill_weight;
  double textured_material_weight = RemovalOptions{}.textured_material_weight;
};

void run_remove(const Options& o) {
  RemovalOptions ro;
  ro.inpainter = o.inpainted.empty() ? o.inpainter : "dir:" + o.inpainted;
  for (const std::string& a : o.ablate) {
    std::stringstream ss(a);
    std::string item;
    while (std::getline(ss, item, ',')) ro.ablate.insert(item);
  }
  ro.finetune_iterations = o.iters;
  ro.view_fill_weight = float(o.view_fill);
  ro.textured_material_weight = float(o.textured_material_weight);
  ro.lighting_relative_fresnel = o.lighting_fresnel == "relative";
  ro.dereflect_lighting = o.lighting_targets == "dereflect";
  ro.device = enum_from_name<DeviceChoice>(o.device).value();  // --device's check accepts only the names
  ro.data = o.data;
  ro.fill_truth = o.fill_truth;
  const bool tty = isatty(STDERR_FILENO);
  int last_step = -1;
  auto progress = [&](const RemovalProgress& p) {
    const int step = int(p.step);
    if (step != last_step && last_step >= 0 && tty) std::fprintf(stderr, "\n");
    last_step = step;
    const double f = double(p.done) / double(p.total);
    if (!tty && !(p.done == p.total || p.done == 0)) return;  // logs: start and end of each step
    char bar[21];
    const int filled = int(f * 20 + 0.5);
    for (int i = 0; i < 20; ++i) bar[i] = i < filled ? '#' : '.';
    bar[20] = 0;
    std::fprintf(stderr, "%s[%d/%d] %-16s [%s] %3.0f%%  %s%s", tty ? "\r" : "", step + 1, kRemovalStepCount,
                 removal_step_name(p.step), bar, 100 * f, p.detail.c_str(), tty ? "\033[K" : "\n");
    std::fflush(stderr);
  };
  RemovalReport r;
  int stopped_by = 0;
  {
    const cli::StopSignals stop;
    try {
      r = run_removal(o.run, ro, progress, stop.flag());
    } catch (...) {
      if (tty) std::fprintf(stderr, "\n");
      throw;
    }
    stopped_by = stop.signal();
  }
  if (tty) std::fprintf(stderr, "\n");
  if (!r.finetune_restarted.empty())
    std::printf("the fine-tune started over: the earlier one in %s was made from other inputs (changed: %s)\n",
                r.out_dir.string().c_str(), r.finetune_restarted.c_str());
  if (r.cancelled) {
    std::printf("interrupted (%s); run the same command again to resume (%s)\n",
                cli::stop_signal_name(stopped_by).c_str(), r.out_dir.string().c_str());
    cli::set_exit_code(128 + stopped_by);
    return;
  }
  double total = 0;
  for (double s : r.seconds) total += s;
  std::string refs;
  for (const auto& v : r.reference_views) refs += (refs.empty() ? "" : ", ") + v;
  std::printf("removed %zu of %zu Gaussians; lighting-aware masks %zu px, inpainting masks %zu px; reference views %s; "
              "lift added %zu; fine-tuned %d iterations; %zu Gaussians, %.0f s\n"
              "result: %s (evaluate with: goris eval %s --split test)\n",
              r.selected, r.gaussians_before, r.lighting_pixels, r.inpaint_pixels, refs.empty() ? "none" : refs.c_str(),
              r.added, r.finetune_iterations, r.gaussians_after, total, r.out_dir.string().c_str(),
              r.out_dir.string().c_str());
}

void setup_remove(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("remove", "Remove the selected object and its reflections from a trained run (stage 2)");
  c->add_option("run", o->run, "Run folder of stage 1 (goris train)")->required();
  auto* inp = c->add_option("--inpainter", o->inpainter,
                            "2D inpainter: harmonic (the default), telea, ns, fsr (OpenCV contrib), or "
                            "\"cmd:COMMAND {image} {mask} {out}\" to run your own per map");
  c->add_option("--inpainted", o->inpainted, "Folder of ready-made inpainted maps (VIEW_MAP.png)")->excludes(inp);
  c->add_option("--ablate", o->ablate, "Switch off a part: " + goris::ablation_help());
  c->add_option("--lighting-fresnel", o->lighting_fresnel,
                 "F in the lighting-aware mask: relative (to the glossy surfaces' F0, default) or absolute (the paper)")
      ->check(CLI::IsMember({"relative", "absolute"}));
  c->add_option("--lighting-targets", o->lighting_targets,
                "The fine-tune inside the lighting-aware mask: dereflect (the photo minus stage 1's estimate of the "
                "target's reflection) or exclude (no photo loss there, the paper)")
      ->check(CLI::IsMember({"dereflect", "exclude"}));
  c->add_option("--iters", o->iters, "Fine-tune iterations (default: 4000 scaled like stage 1)")
      ->check(cli::whole(1, cli::kIntMax));
  c->add_option("--view-fill", o->view_fill,
                "Weight of every other view's own 2D fill of its hole in the fine-tune, where no lifted reference "
                "point lands (0 = the reference views alone)")
      ->capture_default_str()
      ->check(cli::real(0.0, 10.0));
  c->add_option("--textured-material-weight", o->textured_material_weight,
                "Factor on the material targets' weight where the glossy surface's own colour is textured (its "
                "detail round the hole above " +
                    limit_text(SurfaceDetailSettings{}.textured_above) +
                    "): a smooth fill of a veined surface is a wrong target there")
      ->capture_default_str()
      ->check(cli::real(0.0, 10.0));
  c->add_option("--fill-truth", o->fill_truth,
                "A measurement on synthetic scenes, not a removal: a folder of the training views rendered without "
                "the target (VIEW.png; `goris synth --train-after DATA` writes DATA/train_after) that the fine-tune "
                "learns wherever the removal would have made its own targets up: what perfect fills would score");
  cli::add_device_option(*c, o->device);
  cli::add_data_option(*c, o->data);
  c->callback([o] { run_remove(*o); });
}

}  // namespace
GORIS_COMMAND(35, setup_remove);
