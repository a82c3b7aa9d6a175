// `goris bench pipeline --data D1 [D2 ...] | --suite NAME  --configs NAMES --out DIR [--schedule short|medium|full ...]
// [--device D] [--check SUITE.json]`: the paper's ablation ladder (baseline, +elt, +ssf, full, distilled) run end to
// end per scene and schedule, each step a `goris` child process (this binary), so a crash in one configuration is
// recorded and the bench goes on. Writes results.csv, results.md and PSNR-against-time charts (chart.svg/png and
// chart_SCENE.svg/png) with the Pareto front; with --suite (app/bench/bench_suite.h) the scenes are made with
// `goris synth` (cached) and suite.md / suite.json summarise the removal metrics. A configuration whose result.json
// in DIR was made with the same options is reused, not rerun. This file is the command line; the bench is
// app/bench/bench_pipeline.h.
#include <memory>

#include "app/bench/bench_child.h"
#include "app/bench/bench_pipeline.h"
#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "core/util/error.h"

namespace {
using goris::Error;
using goris::bench::pipeline::Bench;
using goris::bench::pipeline::config_names;
using goris::bench::pipeline::Options;

void setup_bench_pipeline(CLI::App& root) {
  auto& bench = goris::bench::bench_group(root);
  auto o = std::make_shared<Options>();
  auto* c = bench.add_subcommand(
      "pipeline", "The ablation ladder end to end per scene and schedule: times, memory, PSNR/SSIM, Pareto chart");
  c->add_option("--data", o->data, "Data set folders (one row block per scene)")->expected(1, -1);
  std::string suites;
  for (const auto& n : goris::bench::suite_names()) suites += (suites.empty() ? "" : ", ") + n;
  c->add_option("--suite", o->suite,
                              "A generalization suite of `goris synth` scenes (" + suites + "; rendered once, cached)");
  c->add_option("--scene-cache", o->scene_cache, "Where the suite's scenes are kept (default OUT/scenes)");
  c->add_option("--scenes", o->suite_scenes, "Only these scenes of the suite (names as in suite.md)")->delimiter(',');
  c->add_option("--check", o->check,
                "A committed suite.json: exit 1 when a scene's changed-region PSNR fell by more than --tolerance");
  c->add_option("--tolerance", o->tolerance_db, "dB of changed-region PSNR that --check accepts")->capture_default_str();
  c->add_option("--publish", o->publish,
                "With --suite: also write suite_SUITE_SCHEDULE.md/.json/_sheet.png, self-contained, into this folder");
  c->add_option("--configs", o->configs, "Comma-separated: " + config_names() + " or all")->capture_default_str();
  c->add_option("--resolution", o->resolution, "Train and evaluate at this image width (0 = the data set's)")
      ->capture_default_str()
      ->check(goris::cli::whole(0, 8192));
  c->add_option("--init-points", o->init_points, "Random initial points of every stage 1 (0 = goris train's default)")
      ->capture_default_str()
      ->check(goris::cli::whole(0, 100000000));
  c->add_option("--out", o->out, "Output folder (results.csv, results.md, chart*.svg/png, runs/)")->required();
  c->add_option("--schedule", o->schedules, "short (500 iterations), medium (2000), long (8000), full (30000); repeatable")
      ->capture_default_str()
      ->expected(1, -1)
      ->check(CLI::Validator(
          [](std::string& s) {  // "tiny" is the CLI test's schedule, left out of the help
            return s == "short" || s == "medium" || s == "long" || s == "full" || s == "tiny" ? std::string()
                                                                                 : "unknown schedule '" + s + "'";
          },
          "short|medium|long|full"));
  goris::cli::add_device_option(*c, o->device);
  c->add_option("--time-axis", o->time_axis,
                 "Time of the chart and the ratios: wall, cpu (the steps' CPU seconds: fairer on a shared machine) or "
                 "auto (cpu when every result ran on the CPU and has it)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "wall", "cpu"}));
  c->add_flag("--keep-stage1", o->keep_stage1,
              "Reuse stage-1 runs in --out that another build of goris trained with the same arguments (to "
              "measure a change of the removal alone); without it only this binary's own runs are reused");
  c->add_flag("--report-only", o->report_only,
              "Write the tables and charts from the results already in --out; configurations without one are "
              "listed as not run");
  c->callback([o, c] {
    if (o->data.empty() && o->suite.empty()) throw Error("goris bench pipeline", "give --data DIR... or --suite NAME");
    // A suite's own defaults: the default against the baseline at its schedule, from 30K random points.
    if (!o->suite.empty()) {
      if (c->count("--configs") == 0) o->configs = "baseline,default";
      if (c->count("--schedule") == 0) o->schedules = {o->suite == "fast" ? "short" : "medium"};
      if (c->count("--init-points") == 0) o->init_points = 30000;
    }
    Bench(*o).run();
  });
}

}  // namespace
GORIS_COMMAND(85, setup_bench_pipeline);
