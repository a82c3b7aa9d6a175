// `goris bench pipeline --data D1 [D2 ...] | --suite NAME  --configs NAMES --out DIR [--schedule short|medium|full ...]
// [--device D] [--check SUITE.json]`: the paper's ablation ladder (baseline, +elt, +ssf, full, distilled) run end to end per scene
// and schedule, each step a `goris` child process (this binary), so a crash in one configuration is recorded
// and the bench goes on. Writes results.csv, results.md and PSNR-against-time charts (chart.svg/png and
// chart_SCENE.svg/png) with the Pareto front; with --suite (app/goris/bench_suite.h) the scenes are made with
// `goris synth` (cached) and suite.md / suite.json summarise the removal metrics. A configuration whose result.json in DIR was made with the
// same options is reused, not rerun.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/goris/bench_child.h"
#include "app/goris/bench_suite.h"
#include "app/goris/command.h"
#include "app/goris/number_checks.h"
#include "core/io/file_bytes.h"
#include "core/report/chart.h"
#include "core/report/pareto.h"
#include "core/train/train_config.h"
#include "core/util/fnv1a.h"
#include "core/util/error.h"
#include "render/removal/removal_pipeline.h"

namespace {
namespace fs = std::filesystem;
using goris::Error;
using nlohmann::json;
using goris::bench::csv_field;
using goris::bench::fmt;
using goris::bench::json_number;
using goris::bench::md_cell;
using goris::bench::read_json_object;
using goris::bench::run_child;
using goris::bench::Schedule;
using goris::bench::schedule_of;
using goris::bench::StepRun;
using goris::bench::write_text;

// The ladder, in the paper's order: each rung adds one part.
struct ConfigSpec {
  const char* name;
  const char* stage1;  // key of the shared stage-1 run
  std::vector<std::string> train_args;
  const char* ablate;  // remove --ablate, "" = none
  bool distill;
  const char* description;
  std::vector<std::string> remove_args = {};  // further `goris remove` options
};

const std::vector<ConfigSpec>& ladder() {
  static const std::vector<ConfigSpec> specs = {
      {"baseline", "radiance", {"--mode", "radiance"}, "material,lamask,twins", false,
       "radiance stage 1; RGB-only inpainting, no lighting-aware mask, no mirror twin, the hole supervised by the "
       "reference views alone (3DGIC's rule)",
       {"--view-fill", "0"}},
      {"default", "default", {}, "", false, "`goris train` and `goris remove` with no options: what a user gets"},
      {"default-noplanar", "default", {}, "twins,reflection", false,
       "default without what the glossy plane gives a radiance run (no planar reflection mask, no surface-only "
       "fill): the removal as it was before them"},
      {"default-nofill", "default", {}, "", false,
       "default without every other view's own fill of its hole (--view-fill 0): the reference views alone "
       "supervise it", {"--view-fill", "0"}},
      {"default-unsup05", "default", {}, "", false,
       "default that also deletes the Gaussians only the target's pixels showed (--unsupported 0.05)",
       {"--unsupported", "0.05"}},
      {"default-unsup20", "default", {}, "", false,
       "default that also deletes the Gaussians only the target's pixels showed (--unsupported 0.2)",
       {"--unsupported", "0.2"}},
      {"+elt", "intrinsic_nossf", {"--mode", "intrinsic", "--set", "intrinsic_screen_space_filter=false"},
       "material,lamask,twins", false, "intrinsic stage 1 with explicit light transport, no screen-space filter"},
      {"+ssf", "intrinsic", {"--mode", "intrinsic"}, "material,lamask,twins", false,
       "intrinsic stage 1 with the screen-space filter"},
      {"full", "intrinsic", {"--mode", "intrinsic"}, "", false, "+ material inpainting, lighting-aware masks (reflections and the target's shadow) and the target's mirror twin"},
      {"planar", "intrinsic_planar", {"--mode", "intrinsic", "--preset", "planar-glossy"}, "", false,
       "full with `--preset planar-glossy` (the table opaque and held to its plane, exact normals)"},
      {"distilled", "intrinsic", {"--mode", "intrinsic"}, "", true,
       "full, exported as a baked (SH) PLY and evaluated as a radiance run"},
      // Modelling no more than a scene needs: each choice against full (and auto against baseline).
      {"auto", "auto", {"--mode", "auto"}, "", false,
       "full where the glossy masks mark >= 0.5 % of the pixels, else radiance, RGB inpainting and the target's shadow "
       "(--mode auto)"},
      {"auto-detect", "auto_detect", {"--mode", "auto", "--set", "use_glossy_masks=false"}, "", false,
       "--mode auto with the glossy masks hidden: glossy regions detected from the photos once the geometry has settled"},
      {"sh1", "intrinsic_sh1", {"--mode", "intrinsic", "--set", "max_sh_degree=1"}, "", false,
       "full with SH degree 1 (the glossy term carries the view dependence)"},
      {"coarse", "intrinsic_coarse", {"--mode", "intrinsic", "--set", "intrinsic_coarse_tracing=true"}, "", false,
       "full with coarse tracing (one reflection ray per block where the glossy filter blurs)"},
  };
  return specs;
}

struct Options {
  std::vector<std::string> data;
  std::string suite;       // a generalization suite (bench_suite.h) instead of, or besides, --data
  std::string scene_cache;  // where the suite's scenes are rendered and kept ("" = OUT/scenes)
  std::set<std::string> suite_scenes;  // only these of the suite (empty: all)
  std::string check;        // a committed suite.json to compare with; a regression fails the bench
  double tolerance_db = 0.5;  // the changed-region PSNR drop --check accepts (the suite's seed-to-seed noise)
  std::string publish;        // also write the suite's summary, self-contained, into this folder (docs/results)
  std::string configs = "baseline,+elt,+ssf,full,distilled";
  std::string out;
  std::vector<std::string> schedules = {"short"};
  std::string device = "auto";
  int resolution = 0;  // training width, 0 = the data set's
  int init_points = 0;  // random initial points, 0 = goris train's default
  bool report_only = false;  // tables and charts from the results in DIR; nothing runs
  bool keep_stage1 = false;  // reuse stage-1 runs another build trained (same arguments and defaults)
  std::string time_axis = "auto";  // wall | cpu | auto (cpu on the CPU when every row has it, else wall)
};

// One row of the results: a configuration on a scene under a schedule.
struct Row {
  std::string scene, config, schedule, status = "failed", error, device;
  bool reused = false;
  int train_iters = 0, remove_iters = 0;
  double gaussians = std::nan(""), psnr = std::nan(""), ssim = std::nan(""), m_psnr = std::nan(""),
         m_ssim = std::nan("");
  double region_psnr = std::nan(""), region_ssim = std::nan(""), region_flip = std::nan(""), flip = std::nan(""),
         ghost_ratio = std::nan("");
  double train_s = 0, select_s = 0, remove_s = 0, export_s = 0, eval_s = 0, peak_mib = 0;
  double peak_device_mib = 0;   // CUDA memory in use at the peak of any step (0 on the CPU)
  double cpu_s = std::nan("");  // CPU seconds of train + select + remove (+ export); NaN in older results
  std::map<std::string, double> remove_steps;
  std::string note;
  double total_s() const { return train_s + select_s + remove_s + export_s; }
};

// The time the chart and the choices table compare: wall seconds, or the steps' CPU seconds.
struct TimeAxis {
  bool cpu = false;
  double of(const Row& r) const { return cpu ? r.cpu_s : r.total_s(); }
  const char* name() const { return cpu ? "CPU" : "total"; }
};

json row_json(const Row& r) {
  return {{"scene", r.scene},       {"config", r.config},         {"schedule", r.schedule},   {"status", r.status},
          {"error", r.error},       {"device", r.device},         {"train_iters", r.train_iters},
          {"remove_iters", r.remove_iters}, {"gaussians", r.gaussians}, {"psnr", r.psnr},  {"ssim", r.ssim},
          {"m_psnr", r.m_psnr},     {"m_ssim", r.m_ssim},         {"train_s", r.train_s},     {"select_s", r.select_s},
          {"remove_s", r.remove_s}, {"export_s", r.export_s},     {"eval_s", r.eval_s},       {"peak_mib", r.peak_mib},
          {"peak_device_mib", r.peak_device_mib}, {"cpu_s", r.cpu_s},       {"remove_steps", r.remove_steps}, {"note", r.note},
          {"region_psnr", r.region_psnr}, {"region_ssim", r.region_ssim}, {"region_flip", r.region_flip},
          {"flip", r.flip}, {"ghost_ratio", r.ghost_ratio}};
}

Row row_from_json(const json& j) {
  Row r;
  auto s = [&](const char* k) { return j.value(k, std::string()); };
  auto d = [&](const char* k) { return j.contains(k) && j[k].is_number() ? j[k].get<double>() : std::nan(""); };
  r.scene = s("scene"), r.config = s("config"), r.schedule = s("schedule"), r.status = s("status");
  r.error = s("error"), r.device = s("device"), r.note = s("note");
  r.train_iters = j.value("train_iters", 0), r.remove_iters = j.value("remove_iters", 0);
  r.gaussians = d("gaussians"), r.psnr = d("psnr"), r.ssim = d("ssim"), r.m_psnr = d("m_psnr"), r.m_ssim = d("m_ssim");
  r.train_s = d("train_s"), r.select_s = d("select_s"), r.remove_s = d("remove_s"), r.export_s = d("export_s");
  r.eval_s = d("eval_s"), r.peak_mib = d("peak_mib"), r.cpu_s = d("cpu_s");
  r.region_psnr = d("region_psnr"), r.region_ssim = d("region_ssim"), r.region_flip = d("region_flip");
  r.flip = d("flip"), r.ghost_ratio = d("ghost_ratio");
  r.peak_device_mib = j.contains("peak_device_mib") ? d("peak_device_mib") : 0.0;
  if (j.contains("remove_steps") && j["remove_steps"].is_object())
    for (auto it = j["remove_steps"].begin(); it != j["remove_steps"].end(); ++it)
      if (it.value().is_number()) r.remove_steps[it.key()] = it.value().get<double>();
  return r;
}

// The host and device peaks of a row so far and those of one more step.
void add_peaks(Row& r, const StepRun& step) {
  r.peak_mib = std::max(r.peak_mib, step.peak_mib);
  r.peak_device_mib = std::max(r.peak_device_mib, step.peak_device_mib);
}

// The device peak as a table cell: `none` when no step used GPU memory.
std::string device_mib(const Row& r, const std::string& none = "") {
  return r.peak_device_mib > 0 ? fmt(r.peak_device_mib, "%.0f") : none;
}

// What `goris train` does with no options: its default configuration. A result of `default` is reused only
// when the defaults it was trained with are today's (other code changes are the --out folder's business,
// as for every configuration).
std::string defaults_fingerprint() {
  nlohmann::json j;
  to_json(j, goris::TrainConfig{});
  j.erase("data");
  j.erase("data_views");  // a record of the data set, not a training setting
  return std::to_string(goris::fnv1a(j.dump()));
}

// Stage 1 of a scene under a schedule, trained once per stage-1 kind and shared by the configurations.
struct Stage1 {
  fs::path run;
  StepRun train;
};

class Bench {
 public:
  explicit Bench(const Options& o) : o_(o), out_(fs::absolute(o.out)) {}

  void run();

 private:
  Stage1 stage1(const std::string& scene, const std::string& data, const Schedule& s, const ConfigSpec& c);
  Row run_config(const std::string& scene, const std::string& data, const Schedule& s, const ConfigSpec& c,
                 const Row* full);
  void evaluate(Row& r, const fs::path& run_dir, const fs::path& logs);
  void write_outputs(const std::vector<Row>& rows, bool final) const;
  void write_suite(const std::vector<Row>& rows, const std::map<std::string, std::string>& kinds) const;
  void publish_suite(std::vector<goris::bench::SuiteResult> results, const std::string& schedule) const;
  std::string stage1_notes(const std::vector<Row>& rows) const;
  bool write_chart(const std::vector<Row>& rows, const std::string& title, const fs::path& stem,
                   const TimeAxis& axis) const;
  TimeAxis time_axis(const std::vector<Row>& rows) const;

  Options o_;
  fs::path out_;
  mutable bool time_axis_is_cpu_ = false;  // what write_suite used, for publish_suite's header
  std::map<std::string, Stage1> stage1_;
};

Stage1 Bench::stage1(const std::string& scene, const std::string& data, const Schedule& s, const ConfigSpec& c) {
  const fs::path dir = out_ / "runs" / scene / s.name / (std::string("stage1_") + c.stage1);
  const std::string key = dir.string();
  if (auto it = stage1_.find(key); it != stage1_.end()) return it->second;
  std::vector<std::string> args = {"train", data, "--out", (dir / "run").string(), "--iters",
                                   std::to_string(s.train_iters), "--device", o_.device, "--checkpoint-every", "0"};
  args.insert(args.end(), c.train_args.begin(), c.train_args.end());
  args.insert(args.end(), s.extra_train_args.begin(), s.extra_train_args.end());
  if (o_.resolution > 0) args.insert(args.end(), {"--resolution", std::to_string(o_.resolution)});
  if (o_.init_points > 0) args.insert(args.end(), {"--init-points", std::to_string(o_.init_points)});
  json options = {{"args", args}};
  // `default` means whatever goris train does with no options: reused only under the same defaults.
  if (c.train_args.empty()) options["defaults"] = defaults_fingerprint();
  Stage1 st{dir / "run", {}};
  // A finished stage 1 with the same arguments, trained by this very binary, is reused with its recorded
  // time; --keep-stage1 also takes one another build trained (to measure a change of the removal alone).
  if (fs::exists(dir / "stage1.json")) {
    const json j = read_json_object(dir / "stage1.json");
    const bool same_binary = j.value("binary", std::string()) == goris::bench::binary_fingerprint();
    if (j.value("options", json()) == options && j.value("ok", false) && (same_binary || o_.keep_stage1)) {
      if (!same_binary) std::printf("    train    --keep-stage1: trained by another build of goris\n");
      st.train = {true, j.value("seconds", 0.0), j.value("peak_mib", 0.0), j.value("peak_device_mib", 0.0), "",
                  json_number(j, "cpu_seconds")};
      std::printf("    train    reused %s\n", st.run.string().c_str());
      return stage1_[key] = st;
    }
  }
  fs::remove_all(dir);
  fs::create_directories(dir);
  st.train = run_child("train", args, dir / "train.log");
  write_text(dir / "stage1.json", json{{"options", options},
                                       {"binary", goris::bench::binary_fingerprint()},
                                       {"ok", st.train.ok},
                                       {"seconds", st.train.seconds},
                                       {"cpu_seconds", st.train.cpu_seconds},
                                       {"peak_mib", st.train.peak_mib},
                                       {"peak_device_mib", st.train.peak_device_mib},
                                       {"error", st.train.error}}
                                          .dump(2));
  return stage1_[key] = st;
}

void Bench::evaluate(Row& r, const fs::path& run_dir, const fs::path& logs) {
  goris::bench::Metrics m;
  const StepRun ev = goris::bench::run_eval(run_dir, o_.device, logs / "eval.log", m);
  r.eval_s = ev.seconds;
  add_peaks(r, ev);
  if (!ev.ok) throw Error(ev.error);
  r.psnr = m.psnr, r.ssim = m.ssim, r.m_psnr = m.m_psnr, r.m_ssim = m.m_ssim, r.gaussians = m.gaussians;
  r.region_psnr = m.region_psnr, r.region_ssim = m.region_ssim, r.region_flip = m.region_flip, r.flip = m.flip;
  r.ghost_ratio = m.ghost_ratio;
  r.device = m.device.empty() ? o_.device : m.device;
}

Row Bench::run_config(const std::string& scene, const std::string& data, const Schedule& s, const ConfigSpec& c,
                      const Row* full) {
  Row r;
  r.scene = scene, r.config = c.name, r.schedule = s.name, r.train_iters = s.train_iters, r.device = o_.device;
  const fs::path dir = out_ / "runs" / scene / s.name / c.name, logs = dir / "logs", run = dir / "run";
  json options = {{"data", data},
                        {"config", c.name},
                        {"schedule", {s.name, s.train_iters, s.remove_iters, s.export_iters, s.extra_train_args}},
                        {"train", c.train_args},
                        {"ablate", c.ablate},
                        {"resolution", o_.resolution},
                        {"device", o_.device}};
  if (o_.init_points > 0) options["init_points"] = o_.init_points;  // absent by default: older results stay reusable
  if (!c.remove_args.empty()) options["remove"] = c.remove_args;
  if (c.train_args.empty()) options["defaults"] = defaults_fingerprint();
  if (const auto row = goris::bench::reusable_row(dir, options, o_.report_only)) {
    Row old = row_from_json(*row);
    old.reused = true;
    std::printf("  %s / %s / %s: reused the result in %s\n", scene.c_str(), s.name.c_str(), c.name, dir.c_str());
    return old;
  }
  if (o_.report_only) {
    r.status = "not run";
    std::printf("  %s / %s / %s: not run (--report-only)\n", scene.c_str(), s.name.c_str(), c.name);
    return r;
  }
  std::printf("  %s / %s / %s: %s\n", scene.c_str(), s.name.c_str(), c.name, c.description);
  fs::remove_all(dir);
  fs::create_directories(logs);
  try {
    fs::path removal;
    if (c.distill && full && full->status == "ok") {
      // distilled = full + export: the full configuration's stage 1 and 2 are its own first steps.
      r.train_s = full->train_s, r.select_s = full->select_s, r.remove_s = full->remove_s, r.cpu_s = full->cpu_s;
      r.remove_steps = full->remove_steps, r.remove_iters = full->remove_iters, r.peak_mib = full->peak_mib;
      r.peak_device_mib = full->peak_device_mib;
      removal = out_ / "runs" / scene / s.name / "full" / "run" / "removal";
      r.note = "stages 1-2 of full (" + removal.parent_path().string() + "); ";
    } else {
      const Stage1 st = stage1(scene, data, s, c);
      r.train_s = st.train.seconds;
      r.cpu_s = st.train.cpu_seconds;
      r.peak_mib = st.train.peak_mib, r.peak_device_mib = st.train.peak_device_mib;
      if (!st.train.ok) throw Error(st.train.error);
      fs::copy(st.run, run, fs::copy_options::recursive);  // each configuration removes in its own copy
      if (std::string(c.stage1).rfind("auto", 0) == 0)  // what --mode auto decided
        r.note += "stage 1 finished as " + read_json_object(run / "config.json").value("mode", std::string("?")) + "; ";
      const StepRun sel =
          run_child("select", {"select", run.string(), "--masks", "--device", o_.device}, logs / "select.log");
      r.select_s = sel.seconds;
      r.cpu_s += sel.cpu_seconds;
      add_peaks(r, sel);
      if (!sel.ok) throw Error(sel.error);
      std::vector<std::string> rm = {"remove", run.string(), "--iters", std::to_string(s.remove_iters), "--device",
                                     o_.device};
      if (*c.ablate) rm.insert(rm.end(), {"--ablate", c.ablate});
      rm.insert(rm.end(), c.remove_args.begin(), c.remove_args.end());
      const StepRun rem = run_child("remove", rm, logs / "remove.log");
      r.remove_s = rem.seconds;
      r.cpu_s += rem.cpu_seconds;
      add_peaks(r, rem);
      if (!rem.ok) throw Error(rem.error);
      removal = run / "removal";
      const json rep = read_json_object(removal / "report.json");
      for (int k = 0; k < goris::kRemovalStepCount; ++k) {
        const char* step = goris::removal_step_name(goris::RemovalStep(k));
        if (rep.contains("seconds") && rep["seconds"].contains(step)) r.remove_steps[step] = rep["seconds"][step];
      }
      r.remove_iters = rep.value("finetune_iterations", s.remove_iters);
      r.peak_mib = std::max(r.peak_mib, rep.value("peak_host_memory_mib", 0.0));
    }
    if (!c.distill) {
      evaluate(r, removal, logs);
    } else {
      const fs::path baked = dir / "baked.ply";
      const StepRun ex = run_child("export",
                                   {"export", removal.string(), "--baked", baked.string(), "--iters",
                                    std::to_string(s.export_iters), "--device", o_.device},
                                   logs / "export.log");
      r.export_s = ex.seconds;
      r.cpu_s += ex.cpu_seconds;
      add_peaks(r, ex);
      if (!ex.ok) throw Error(ex.error);
      // The baked PLY is a plain 3DGS model: evaluate it as a radiance run whose point cloud it is.
      const fs::path baked_run = dir / "baked_run";
      fs::create_directories(baked_run);
      json cfg = read_json_object(removal / "config.json");
      cfg["mode"] = "radiance";
      write_text(baked_run / "config.json", cfg.dump(2) + "\n");
      fs::copy_file(baked, baked_run / "point_cloud.ply", fs::copy_options::overwrite_existing);
      try {
        evaluate(r, baked_run, logs);
        r.note += "metrics of the baked PLY evaluated as a radiance run";
      } catch (const Error& e) {
        // Fall back to the export's own score of the baked model against the test images (PSNR only).
        const json bj = read_json_object(dir / "baked.json");
        r.psnr = bj.contains("gt") ? json_number(bj["gt"], "psnr_baked") : std::nan("");
        r.gaussians = json_number(bj, "gaussians");
        if (!std::isfinite(r.psnr)) throw;
        r.note += std::string("PSNR from the export's baked.json (evaluating the baked run failed: ") + e.what() + ")";
      }
    }
    r.status = "ok";
  } catch (const std::exception& e) {
    r.status = "failed";
    r.error = e.what();
  }
  if (r.note.size() >= 2 && r.note.compare(r.note.size() - 2, 2, "; ") == 0) r.note.resize(r.note.size() - 2);
  goris::bench::write_result(dir, options, row_json(r));
  return r;
}

std::string step_column(std::string step) {
  std::replace(step.begin(), step.end(), ' ', '_');
  std::replace(step.begin(), step.end(), '-', '_');
  return "remove_" + step + "_s";
}

std::string config_names() {
  std::string names;
  for (const auto& c : ladder()) names += (names.empty() ? "" : ", ") + std::string(c.name);
  return names;
}

size_t config_index(const std::string& name) {
  for (size_t i = 0; i < ladder().size(); ++i)
    if (ladder()[i].name == name) return i;
  return 0;
}

// False when no row has a result to draw (no chart then).
bool Bench::write_chart(const std::vector<Row>& rows, const std::string& title, const fs::path& stem,
                        const TimeAxis& axis) const {
  goris::Chart chart;
  chart.title = title;
  chart.x_label = std::string(axis.cpu ? "CPU time" : "total time") +
                  ": train + select + remove (+ export), seconds (log scale)";
  chart.y_label = "PSNR after removal (dB)";
  std::vector<goris::TimeQuality> pts;
  std::set<std::string> configs_seen;
  for (const Row& r : rows) {
    const double t = axis.of(r);
    if (r.status != "ok" || !std::isfinite(r.psnr) || !(t > 0)) continue;
    const size_t ci = config_index(r.config);
    size_t si = std::find(o_.schedules.begin(), o_.schedules.end(), r.schedule) - o_.schedules.begin();
    chart.markers.push_back({t, r.psnr, goris::palette_color(ci), goris::marker_shape(si),
                             r.config + " / " + r.schedule + ": " + fmt(r.psnr, "%.2f") + " dB, " + fmt(t, "%.1f") +
                                 " s"});
    pts.push_back({t, r.psnr});
    configs_seen.insert(r.config);
  }
  if (chart.markers.empty()) return false;
  for (size_t i : goris::pareto_front(pts)) chart.step_line.push_back({pts[i].time, pts[i].quality});
  for (size_t i = 0; i < ladder().size(); ++i)
    if (configs_seen.count(ladder()[i].name))
      chart.legend.push_back({ladder()[i].name, goris::palette_color(i), goris::MarkerShape::Circle, false});
  for (size_t i = 0; i < o_.schedules.size(); ++i)
    chart.legend.push_back({"schedule " + o_.schedules[i], {110, 110, 110}, goris::marker_shape(i), false});
  chart.legend.push_back({"Pareto front", chart.step_color, goris::MarkerShape::Circle, true});
  write_text(fs::path(stem.string() + ".svg"), goris::chart_svg(chart));
  std::vector<unsigned char> png;
  cv::imencode(".png", goris::chart_image(chart), png);
  goris::write_file_bytes(fs::path(stem.string() + ".png"), png.data(), png.size());
  return true;
}

// What each configuration saves in time and costs in PSNR against full and against baseline, per scene and
// schedule (empty when neither reference succeeded).
std::string choices_table(const std::vector<Row>& rows, const TimeAxis& axis) {
  auto find = [&](const Row& like, const char* config) -> const Row* {
    for (const Row& r : rows)
      if (r.scene == like.scene && r.schedule == like.schedule && r.config == config && r.status == "ok") return &r;
    return nullptr;
  };
  auto against = [&](const Row& r, const Row* ref) {
    if (!ref || !(axis.of(*ref) > 0)) return std::string(" | | ");
    return " | " + fmt(axis.of(r) / axis.of(*ref), "%.2fx") + " | " + fmt(r.psnr - ref->psnr, "%+.2f");
  };
  std::string t;
  for (const Row& r : rows) {
    if (r.status != "ok" || r.config == "full" || r.config == "baseline") continue;
    const Row *full = find(r, "full"), *base = find(r, "baseline");
    if (!full && !base) continue;
    t += "| " + md_cell(r.scene) + " | " + r.schedule + " | " + r.config + " | " + fmt(axis.of(r), "%.1f") + " | " +
         fmt(r.psnr, "%.2f") + against(r, full) + against(r, base) + " |\n";
  }
  if (t.empty()) return t;
  return "\nEach choice against `full` and `baseline` (same scene and schedule): time ratio (" +
         std::string(axis.cpu ? "CPU" : "total wall") + " time) and PSNR difference after removal.\n\n| scene | schedule "
         "| config | " + axis.name() + " s | PSNR | time vs full | ΔPSNR vs full | time vs baseline | ΔPSNR vs "
         "baseline |\n|---|---|---|--:|--:|--:|--:|--:|--:|\n" + t;
}

// What the stage-1 runs said about the choices (read from their logs, so reused rows have them too): rays
// traced and saved per shaded frame, --mode auto's decision.
std::string Bench::stage1_notes(const std::vector<Row>& rows) const {
  std::set<fs::path> seen;
  std::string t;
  for (const Row& r : rows) {
    const auto spec = std::find_if(ladder().begin(), ladder().end(), [&](const ConfigSpec& c) { return c.name == r.config; });
    if (spec == ladder().end()) continue;
    const fs::path log = out_ / "runs" / r.scene / r.schedule / (std::string("stage1_") + spec->stage1) / "train.log";
    if (!seen.insert(log).second || !fs::exists(log)) continue;
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);) {
      const bool wanted = line.rfind("reflection rays:", 0) == 0 || line.rfind("--mode auto", 0) == 0;
      if (wanted) t += "- " + md_cell(r.scene) + " / " + r.schedule + " / stage 1 `" + spec->stage1 + "`: " + md_cell(line) + "\n";
    }
  }
  return t.empty() ? t : "\nStage-1 runs (from their logs):\n\n" + t;
}

void Bench::write_outputs(const std::vector<Row>& rows, bool final) const {
  std::vector<std::string> steps;
  for (int k = 0; k < goris::kRemovalStepCount; ++k) steps.push_back(goris::removal_step_name(goris::RemovalStep(k)));

  std::string csv = "scene,config,schedule,status,device,train_iters,remove_iters,gaussians,psnr,ssim,m_psnr,m_ssim,"
                    "region_psnr,region_ssim,region_flip,flip,ghost_ratio,train_s,select_s,remove_s";
  for (const auto& s : steps) csv += "," + step_column(s);
  csv += ",export_s,eval_s,total_s,cpu_s,peak_host_mib,peak_device_mib,reused,error,note\n";
  for (const Row& r : rows) {
    csv += csv_field(r.scene) + "," + csv_field(r.config) + "," + r.schedule + "," + r.status + "," +
           csv_field(r.device) + "," + std::to_string(r.train_iters) + "," + std::to_string(r.remove_iters) + "," +
           fmt(r.gaussians, "%.0f") + "," + fmt(r.psnr, "%.3f") + "," + fmt(r.ssim, "%.4f") + "," +
           fmt(r.m_psnr, "%.3f") + "," + fmt(r.m_ssim, "%.4f") + "," + fmt(r.region_psnr, "%.3f") + "," +
           fmt(r.region_ssim, "%.4f") + "," + fmt(r.region_flip, "%.4f") + "," + fmt(r.flip, "%.4f") + "," +
           fmt(r.ghost_ratio, "%.3f") + "," + fmt(r.train_s, "%.2f") + "," +
           fmt(r.select_s, "%.2f") + "," + fmt(r.remove_s, "%.2f");
    for (const auto& s : steps) csv += "," + (r.remove_steps.count(s) ? fmt(r.remove_steps.at(s), "%.2f") : "");
    csv += "," + fmt(r.export_s, "%.2f") + "," + fmt(r.eval_s, "%.2f") + "," + fmt(r.total_s(), "%.2f") + "," +
           fmt(r.cpu_s, "%.2f") + "," + fmt(r.peak_mib, "%.0f") + "," + device_mib(r) + "," + (r.reused ? "yes" : "no") + "," + csv_field(r.error) + "," +
           csv_field(r.note) + "\n";
  }
  write_text(out_ / "results.csv", csv);

  std::string md = "# GOR-IS pipeline bench\n\n";
  md += "Configurations (the paper's ablation ladder, then the choices that model no more than a scene needs):\n\n";
  for (const auto& c : ladder()) md += std::string("- `") + c.name + "`: " + c.description + "\n";
  md += "\nSchedules: ";
  for (size_t i = 0; i < o_.schedules.size(); ++i) {
    const Schedule s = schedule_of(o_.schedules[i]);
    md += (i ? "; " : "") + s.name + " = " + std::to_string(s.train_iters) + " stage-1 iterations, " +
          std::to_string(s.remove_iters) + " fine-tune, " + std::to_string(s.export_iters) + " distillation";
  }
  md += ". Device requested: `" + o_.device + "`.\n\n";
  const TimeAxis axis = time_axis(rows);
  md += "Times are wall seconds of each step's process; total = train + select + remove (+ export), evaluation "
        "excluded; CPU = the same steps' CPU seconds (user + system, all threads), which other jobs on the machine "
        "barely change. The chart and the ratios below use " + std::string(axis.cpu ? "CPU" : "total wall") +
        " time. Stage 1 is trained once per kind and shared (its time is counted in each configuration that "
        "uses it). Metrics: test views against the after-removal ground truth; M-PSNR / M-SSIM inside the "
        "target's region; region PSNR and ghost inside the region the removal changes (`goris eval`, on data "
        "sets with `full_` views); FLIP: LDR-FLIP over the whole image. Peak memory: the largest resident set (host) and the most CUDA memory in use (device; - "
        "on the CPU) of any step's process.\n\n";
  md += "| scene | config | schedule | status | train s | select s | remove s | export s | eval s | total s | CPU s "
        "| host MiB | device MiB | Gaussians | PSNR | SSIM | M-PSNR | M-SSIM | region PSNR | ghost | FLIP | device |\n";
  md += "|---|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|\n";
  for (const Row& r : rows)
    md += "| " + md_cell(r.scene) + " | " + r.config + " | " + r.schedule + " | " + r.status + (r.reused ? " (reused)" : "") +
          " | " + fmt(r.train_s, "%.1f") + " | " + fmt(r.select_s, "%.1f") + " | " + fmt(r.remove_s, "%.1f") + " | " +
          fmt(r.export_s, "%.1f") + " | " + fmt(r.eval_s, "%.1f") + " | " + fmt(r.total_s(), "%.1f") + " | " +
          fmt(r.cpu_s, "%.1f") + " | " + fmt(r.peak_mib, "%.0f") + " | " + device_mib(r, "-") + " | " + fmt(r.gaussians, "%.0f") + " | " + fmt(r.psnr, "%.2f") + " | " +
          fmt(r.ssim, "%.4f") + " | " + fmt(r.m_psnr, "%.2f") + " | " + fmt(r.m_ssim, "%.4f") + " | " +
          fmt(r.region_psnr, "%.2f") + " | " + fmt(r.ghost_ratio, "%.2f") + " | " + fmt(r.flip, "%.3f") + " | " +
          md_cell(r.device) + " |\n";
  std::string notes;
  for (const Row& r : rows) {
    if (!r.error.empty()) notes += "- " + r.scene + " / " + r.config + " / " + r.schedule + ": **failed**: " + md_cell(r.error) + "\n";
    if (!r.note.empty()) notes += "- " + r.scene + " / " + r.config + " / " + r.schedule + ": " + md_cell(r.note) + "\n";
  }
  if (!notes.empty()) md += "\nNotes:\n\n" + notes;
  md += choices_table(rows, axis);
  md += stage1_notes(rows);

  std::vector<std::string> scenes;
  for (const Row& r : rows)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  // The overall chart: one marker per configuration x schedule, the mean over the scenes. A configuration
  // that did not succeed on every scene is left out: its mean would compare other scenes than its neighbours'.
  std::vector<Row> means;
  std::string partial;
  for (const auto& c : ladder())
    for (const auto& s : o_.schedules) {
      Row m;  // its time is the mean of the rows' times on the chosen axis (kept in train_s and cpu_s alike)
      m.config = c.name, m.schedule = s, m.status = "ok", m.psnr = 0;
      int n = 0;
      for (const Row& r : rows)
        if (r.config == c.name && r.schedule == s && r.status == "ok" && std::isfinite(r.psnr)) {
          m.psnr += r.psnr, m.train_s += axis.of(r), ++n;
        }
      if (n == 0) continue;
      if (n < int(scenes.size())) {
        partial += (partial.empty() ? "" : ", ") + std::string(c.name) + " / " + s + " (" + std::to_string(n) + " of " +
                   std::to_string(scenes.size()) + ")";
        continue;
      }
      m.psnr /= n, m.train_s /= n, m.cpu_s = m.train_s;
      means.push_back(m);
    }
  std::vector<std::string> missing;  // charts with nothing to draw
  const std::string title = scenes.size() == 1 ? "PSNR against time: " + scenes[0]
                                               : "PSNR against time: mean over " + std::to_string(scenes.size()) + " scenes";
  if (!partial.empty()) md += "\nLeft out of the mean chart (a result on only some of the scenes): " + partial + ".\n";
  if (write_chart(means, title, out_ / "chart", axis)) md += "\n![PSNR against time](chart.png)\n";
  else missing.push_back("chart");
  for (const auto& sc : scenes) {
    std::vector<Row> mine;
    for (const Row& r : rows)
      if (r.scene == sc) mine.push_back(r);
    if (write_chart(mine, "PSNR against time: " + sc, out_ / ("chart_" + sc), axis)) md += "\n![" + sc + "](chart_" + sc + ".png)\n";
    else missing.push_back("chart_" + sc);
  }
  write_text(out_ / "results.md", md);
  if (final)
    for (const auto& m : missing) std::printf("no successful configuration with a PSNR: no %s.svg/png\n", m.c_str());
}

// suite.md / suite.json: the removal metrics per scene against baseline, the goals, and with --check the
// regressions against a committed suite.json (each printed; the bench then exits 1).
void Bench::write_suite(const std::vector<Row>& rows, const std::map<std::string, std::string>& kinds) const {
  const TimeAxis axis = time_axis(rows);
  time_axis_is_cpu_ = axis.cpu;
  for (const auto& sched : o_.schedules) {
    std::vector<goris::bench::SuiteResult> results;
    for (const Row& r : rows) {
      if (r.schedule != sched || !kinds.count(r.scene)) continue;
      goris::bench::SuiteResult s;
      s.scene = r.scene, s.kind = kinds.at(r.scene), s.config = r.config, s.ok = r.status == "ok";
      s.psnr = r.psnr, s.region_psnr = r.region_psnr, s.region_ssim = r.region_ssim, s.region_flip = r.region_flip;
      s.flip = r.flip, s.ghost_ratio = r.ghost_ratio, s.seconds = axis.of(r);
      const fs::path sheet = fs::path("runs") / r.scene / sched / r.config / "run" / "removal" / "metrics_removal.png";
      if (fs::exists(out_ / sheet)) s.contact_sheet = sheet.string();
      results.push_back(s);
    }
    auto sum = goris::bench::summarize_suite(o_.suite, sched, results, "baseline");
    const std::string stem = o_.schedules.size() == 1 ? "suite" : "suite_" + sched;
    if (goris::bench::write_suite_sheet(results, out_, out_ / (stem + "_sheet.png")))
      sum.markdown += "\nEvery scene's test view with the largest changed region: `full_` | `r_` | each configuration's "
                      "render after removal (" + o_.configs + "): [" + stem + "_sheet.png](" + stem + "_sheet.png)\n";
    write_text(out_ / (stem + ".md"), sum.markdown);
    write_text(out_ / (stem + ".json"), sum.json.dump(2) + "\n");
    std::printf("wrote %s and %s\n", (out_ / (stem + ".md")).c_str(), (out_ / (stem + ".json")).c_str());
    if (!o_.publish.empty()) publish_suite(results, sched);
    if (o_.check.empty()) continue;
    const json committed = read_json_object(o_.check);
    if (committed.value("schedule", "") != sched) continue;
    const auto bad = goris::bench::suite_regressions(committed, sum.json, o_.tolerance_db);
    if (bad.empty()) {
      std::printf("suite check against %s: no regression (tolerance %.2f dB)\n", o_.check.c_str(), o_.tolerance_db);
      continue;
    }
    std::printf("\nSUITE REGRESSION against %s (tolerance %.2f dB):\n", o_.check.c_str(), o_.tolerance_db);
    for (const auto& b : bad) std::printf("  %s\n", b.c_str());
    goris::cli::set_exit_code(1);
  }
}

// --publish DIR: DIR/suite_SUITE_SCHEDULE.md / .json / _sheet.png, self-contained (no links into the bench
// folder), headed by the command that reproduces them and the machine they ran on.
void Bench::publish_suite(std::vector<goris::bench::SuiteResult> results, const std::string& schedule) const {
  const fs::path dir = fs::absolute(o_.publish);
  fs::create_directories(dir);
  const std::string stem = "suite_" + o_.suite + "_" + schedule;
  const bool sheet = goris::bench::write_suite_sheet(results, out_, dir / (stem + "_sheet.png"));
  for (auto& r : results) r.contact_sheet.clear();
  auto sum = goris::bench::summarize_suite(o_.suite, schedule, results, "baseline");
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  std::string cmd = "goris bench pipeline --suite " + o_.suite + " --configs " + o_.configs + " --schedule " + schedule;
  if (o_.init_points != 30000) cmd += " --init-points " + std::to_string(o_.init_points);
  if (o_.resolution > 0) cmd += " --resolution " + std::to_string(o_.resolution);
  if (!o_.suite_scenes.empty()) {
    std::string names;
    for (const std::string& n : o_.suite_scenes) names += (names.empty() ? "" : ",") + n;
    cmd += " --scenes " + names;
  }
  // The folder as a reader finds it: relative to where the bench ran when it lies below (docs/results).
  const fs::path rel = dir.lexically_relative(fs::current_path());
  const bool below = !rel.empty() && *rel.begin() != "..";
  cmd += " --device " + o_.device + " --out DIR --publish " + (below ? rel.generic_string() : o_.publish);
  std::string head = "Reproduce with `" + cmd + "` (scenes: `goris synth`, rendered once into DIR/scenes or "
                     "--scene-cache). Machine: " + cpu + ", " + std::to_string(std::thread::hardware_concurrency()) +
                     " threads; times are " + (time_axis_is_cpu_ ? "CPU" : "wall") + " seconds of train + select + remove.\n\n";
  const auto at = sum.markdown.find("\n\n");
  sum.markdown.insert(at == std::string::npos ? 0 : at + 2, head);
  if (sheet)
    sum.markdown += "\n![Every scene's test view with the largest changed region: full_ | r_ | each configuration's "
                    "render after removal](" + stem + "_sheet.png)\n";
  sum.json["command"] = cmd;
  write_text(dir / (stem + ".md"), sum.markdown);
  write_text(dir / (stem + ".json"), sum.json.dump(2) + "\n");
  std::printf("published %s\n", (dir / (stem + ".md")).c_str());
}

TimeAxis Bench::time_axis(const std::vector<Row>& rows) const {
  TimeAxis a;
  if (o_.time_axis == "wall") return a;
  bool all_cpu = true, any = false;  // rows from before CPU times were recorded have none
  for (const Row& r : rows)
    if (r.status == "ok") any = true, all_cpu = all_cpu && r.cpu_s > 0;
  if (o_.time_axis == "cpu") {
    if (any && !all_cpu) throw Error("--time-axis cpu", "some results have no CPU time (written before it was "
                                                        "recorded): rerun them, or use --time-axis wall");
    a.cpu = true;
    return a;
  }
  // auto: CPU seconds measure the work when the steps ran on the CPU; on a GPU they measure the host's waiting.
  bool on_cpu = true;
  for (const Row& r : rows)
    if (r.status == "ok") on_cpu = on_cpu && r.device == "cpu";
  a.cpu = any && all_cpu && on_cpu;
  return a;
}

void Bench::run() {
  std::vector<const ConfigSpec*> configs;
  std::stringstream ss(o_.configs);
  for (std::string name; std::getline(ss, name, ',');) {
    if (name.empty()) continue;
    if (name == "all") {
      for (const auto& c : ladder()) configs.push_back(&c);
      continue;
    }
    const auto it = std::find_if(ladder().begin(), ladder().end(), [&](const ConfigSpec& c) { return c.name == name; });
    if (it == ladder().end()) throw Error("--configs", "unknown configuration '" + name + "' (" + config_names() + ", all)");
    if (std::find(configs.begin(), configs.end(), &*it) == configs.end()) configs.push_back(&*it);
  }
  if (configs.empty()) throw Error("--configs", "no configuration named");
  // Ladder order (the pointers point into ladder()), so that distilled finds full's result when both run.
  std::sort(configs.begin(), configs.end());
  std::vector<std::string> schedules;
  for (const auto& s : o_.schedules)
    if (std::find(schedules.begin(), schedules.end(), s) == schedules.end()) schedules.push_back(s);
  o_.schedules = schedules;
  std::vector<std::pair<std::string, std::string>> scenes;  // name, absolute data path
  std::map<std::string, std::string> kinds;                  // suite scenes: their kind
  if (!o_.suite.empty()) {
    const auto& suite = goris::bench::suite_scenes(o_.suite);
    const fs::path cache = o_.scene_cache.empty() ? out_ / "scenes" : fs::absolute(o_.scene_cache);
    for (const auto& name : o_.suite_scenes)
      if (std::none_of(suite.begin(), suite.end(), [&](const auto& sc) { return sc.name == name; }))
        throw Error("--scenes", "suite '" + o_.suite + "' has no scene '" + name + "'");
    std::printf("suite %s: %zu scenes in %s\n", o_.suite.c_str(), suite.size(), cache.c_str());
    for (const auto& sc : suite) {
      if (!o_.suite_scenes.empty() && !o_.suite_scenes.count(sc.name)) continue;
      const fs::path dir =
          goris::bench::ensure_suite_scene(sc, cache, fs::path(GORIS_RESOURCE_DIR) / "synth" / "render_scene.py");
      scenes.push_back({sc.name, dir.string()});
      kinds[sc.name] = sc.kind;
    }
  }
  for (const auto& d : o_.data) {
    if (!fs::is_directory(d)) throw Error(d, "not a data set folder");
    const fs::path abs = fs::weakly_canonical(fs::absolute(d));
    std::string name = abs.filename().string();
    for (int k = 2; std::any_of(scenes.begin(), scenes.end(), [&](const auto& s) { return s.first == name; }); ++k)
      name = abs.filename().string() + "_" + std::to_string(k);
    scenes.push_back({name, abs.string()});
  }
  if (fs::exists(out_) && !fs::is_directory(out_)) throw Error(out_.string(), "exists and is not a folder");
  fs::create_directories(out_ / "runs");

  std::vector<Row> rows;
  for (const auto& [scene, data] : scenes)
    for (const auto& sched : o_.schedules) {
      const Schedule s = schedule_of(sched);
      std::optional<Row> full;
      for (const ConfigSpec* c : configs) {
        rows.push_back(run_config(scene, data, s, *c, full ? &*full : nullptr));
        if (std::string(c->name) == "full") full = rows.back();
        write_outputs(rows, false);  // a long bench shows its results so far
      }
    }
  std::printf("\n");
  write_outputs(rows, true);
  if (!o_.suite.empty()) write_suite(rows, kinds);
  int failed = 0;
  for (const Row& r : rows) failed += r.status == "failed";
  std::printf("wrote %s, %s and the charts in %s (%zu rows, %d failed)\n", (out_ / "results.csv").c_str(),
              (out_ / "results.md").c_str(), out_.c_str(), rows.size(), failed);
  if (failed) goris::cli::set_exit_code(1);
}

void setup_bench_pipeline(CLI::App& root) {
  auto& bench = goris::cli::subcommand_group(root, "bench", "Benchmarks (medians, with the machine and sizes)");
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
  c->add_option("--device", o->device, "auto | cpu | cuda")->check(CLI::IsMember({"auto", "cpu", "cuda"}));
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
