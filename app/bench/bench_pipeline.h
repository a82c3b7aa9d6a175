#pragma once
// `goris bench pipeline`'s parts (the command line is in cmd_bench_pipeline.cpp): the configurations it
// knows (bench_pipeline_configs.cpp), a result row and its JSON (bench_pipeline_rows.cpp), running the
// stages as child processes (bench_pipeline_run.cpp) and the tables, charts and suite summary it writes
// (bench_pipeline_report.cpp).
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/bench_child.h"
#include "app/bench/bench_suite.h"

namespace goris::bench::pipeline {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The ladder, in the paper's order: each rung adds one part.
struct ConfigSpec {
  const char* name;
  const char* stage1;  // key of the shared stage-1 run
  std::vector<std::string> train_args;
  const char* ablate;  // remove --ablate, "" = none
  bool distill;
  const char* description;
  std::vector<std::string> remove_args = {};  // further `goris remove` options
  // A measurement, not a removal: `goris remove --fill-truth DATA/train_after` (rendered first with
  // `goris synth --train-after` when missing; synth data sets only).
  bool true_fills = false;
};

// Every configuration, in ladder order.
const std::vector<ConfigSpec>& ladder();
// "baseline, default, ..." for the help and errors.
std::string config_names();
// Its position in ladder() (0 when unknown).
std::size_t config_index(const std::string& name);
// What `goris train` does with no options: its default configuration. A result of `default` is reused only
// when the defaults it was trained with are today's (other code changes are the --out folder's business,
// as for every configuration).
std::string defaults_fingerprint();

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
  double ghost_floor = std::nan("");  // stage 1's own part of the ghost (goris eval); NaN in older results
  double stage1_glossy_share = std::nan("");  // Metrics::stage1_glossy_share; NaN for radiance runs and older results
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

json row_json(const Row& r);
Row row_from_json(const json& j);
// The host and device peaks of a row so far and those of one more step.
void add_peaks(Row& r, const StepRun& step);
// The device peak as a table cell: `none` when no step used GPU memory.
std::string device_mib(const Row& r, const std::string& none = "");
// "remove_STEP_s": the results table's column of a removal step.
std::string step_column(std::string step);

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
  // kinds: each suite scene's kind; images: its scene_images_fingerprint.
  void write_suite(const std::vector<Row>& rows, const std::map<std::string, std::string>& kinds,
                   const std::map<std::string, std::string>& images) const;
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

}  // namespace goris::bench::pipeline
