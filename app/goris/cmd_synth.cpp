// `goris synth --preset NAME --out DIR ...`: renders a GOR-IS style data set with Blender Cycles
// (tools/synth: preset -> scene.json -> resources/synth/render_scene.py run by `blender -b`).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli_common/command.h"
#include "tools/synth/synth.h"

namespace {
namespace fs = std::filesystem;

std::string clock_text(double seconds) {
  int s = int(seconds + 0.5);
  char b[32];
  std::snprintf(b, sizeof b, "%d:%02d", s / 60, s % 60);
  return b;
}

void setup_synth(CLI::App& root) {
  struct Args {
    goris::synth::SynthOptions opt;
    std::string out, blender, train_after;
    bool contact_sheet = false, no_gt = false;
  };
  auto a = std::make_shared<Args>();
  std::string presets;
  for (const auto& p : goris::synth::preset_names()) presets += (presets.empty() ? "" : ", ") + p;
  auto* c = root.add_subcommand("synth", "Render a synthetic GOR-IS data set with Blender Cycles (needs `blender`)");
  c->add_option("--preset", a->opt.preset, "scene preset: " + presets)->capture_default_str();
  auto* out_opt = c->add_option("--out", a->out, "output data set folder");
  c->add_option("--train-after", a->train_after,
                "instead of a new data set: render the training views of this synth data set once more without "
                "the target, into DATA/train_after/ (what `goris remove --fill-truth` reads)")
      ->excludes(out_opt);
  c->add_option("--res", a->opt.resolution, "image width and height in pixels")->capture_default_str();
  c->add_option("--spp", a->opt.samples, "Cycles samples per pixel")->capture_default_str();
  c->add_option("--train", a->opt.train_views, "training views")->capture_default_str();
  c->add_option("--test", a->opt.test_views, "test views (new viewpoints)")->capture_default_str();
  c->add_option("--seed", a->opt.seed, "random seed of the preset")->capture_default_str();
  c->add_option("--table-roughness", a->opt.table_roughness,
                 "override the glossy table top's roughness (0 = mirror .. 1; presets with a table)")
      ->check(CLI::Range(0.0, 1.0));
  auto names = [](const std::vector<std::string>& v) {
    std::string t;
    for (const auto& n : v) t += (t.empty() ? "" : "|") + n;
    return t;
  };
  c->add_option("--table-material", a->opt.table_material,
                "override the table top's material: " + names(goris::synth::table_material_names()));
  c->add_option("--table-shape", a->opt.table_shape,
                "override the glossy surface's shape: " + names(goris::synth::table_shape_names()));
  c->add_option("--target-shape", a->opt.target_shape,
                "override the target's shape: " + names(goris::synth::target_shape_names()));
  c->add_option("--objects", a->opt.objects, "override the number of diffuse objects besides the target (0-6)");
  c->add_option("--camera-elevation", a->opt.camera_elevation,
                "override the cameras' elevations: " + names(goris::synth::camera_elevation_names()));
  c->add_option("--blender", a->blender, "Blender executable (default: blender on PATH)");
  c->add_flag("--contact-sheet", a->contact_sheet, "also write contact_sheet.png (test views: full_ | r_ | mask)");
  c->add_flag("--no-gt", a->no_gt, "skip the intrinsic ground-truth maps (train/gt/*.exr)");
  c->callback([a] {
    const fs::path script = fs::path(GORIS_RESOURCE_DIR) / "synth" / "render_scene.py";
    auto start = std::chrono::steady_clock::now();
    auto elapsed = [start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    auto on_frame = [elapsed](int done, int total) {
      double t = elapsed();
      std::fprintf(stderr, "\rrendering view %d/%d  elapsed %s  ETA %s   ", done, total, clock_text(t).c_str(),
                   clock_text(t / done * (total - done)).c_str());
      std::fflush(stderr);
    };
    auto run = [](const auto& f) {
      try {
        f();
      } catch (...) {
        std::fprintf(stderr, "\n");  // end the progress line before main prints the error
        throw;
      }
      std::fprintf(stderr, "\n");
    };
    if (!a->train_after.empty()) {
      goris::synth::TrainAfterJob job{a->train_after, script, a->blender, on_frame};
      std::fprintf(stderr, "starting Blender (the training views of %s without the target)...\n", a->train_after.c_str());
      run([&] { goris::synth::render_train_after(job); });
      std::printf("wrote %s in %s\n", (fs::path(a->train_after) / "train_after").string().c_str(),
                  clock_text(elapsed()).c_str());
      return;
    }
    if (a->out.empty()) throw CLI::RequiredError("--out (or --train-after DATA)");
    goris::synth::SynthJob job;
    job.options = a->opt;
    job.options.ground_truth_maps = !a->no_gt;
    job.out = a->out;
    job.blender = a->blender;
    job.script = script;
    job.contact_sheet = a->contact_sheet;
    job.on_frame = on_frame;
    std::fprintf(stderr, "starting Blender (preset %s, %dx%d, %d spp, %d train + %d test views)...\n",
                 a->opt.preset.c_str(), a->opt.resolution, a->opt.resolution, a->opt.samples, a->opt.train_views,
                 a->opt.test_views);
    run([&] { goris::synth::run_synth(job); });
    std::printf("wrote %s in %s (%d train, %d test views)\n", a->out.c_str(), clock_text(elapsed()).c_str(),
                a->opt.train_views, a->opt.test_views);
  });
}
}  // namespace
GORIS_COMMAND(15, setup_synth);
