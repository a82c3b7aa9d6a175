#pragma once
// What the end-to-end `goris bench` commands (pipeline, stability) share: each step runs as a child `goris`
// process (this very binary, through posix_spawn) with its own log, so a crash or an error in one step is a
// recorded failure and the bench goes on; their schedules; and the small JSON / CSV / markdown helpers of
// their result tables.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_common/json_number.h"

namespace CLI {
class App;
}

namespace goris::bench {

// The `goris bench` group that every benchmark command adds itself to (created by the first).
CLI::App& bench_group(CLI::App& root);


// One child process: whether it exited 0, its wall time, its peak resident memory, when it failed a message
// "STEP failed (exit code N | killed by signal S): <its error line> [log LOG]", and its CPU time (user +
// system, all threads): unlike wall time it barely moves when other jobs share the machine.
struct StepRun {
  bool ok = false;
  double seconds = 0;
  double peak_mib = 0;         // host: the child's largest resident set
  double peak_device_mib = 0;  // CUDA memory in use at the child's peak (0: no GPU memory, or unknown)
  std::string error;
  double cpu_seconds = 0;
};

// Runs `goris ARGS` with stdout and stderr in `log` (created or truncated), printing the command line and
// the outcome under the label `step`.
StepRun run_child(const std::string& step, std::vector<std::string> args, const std::filesystem::path& log);

// The `error: ...` line of a failed step's log (main prints it), else its last non-empty line; "" when the
// log cannot be read.
std::string failure_message(const std::filesystem::path& log);

// The means of `goris eval`'s metrics.json (NaN where absent or null: e.g. a mean over non-finite renders).
struct Metrics {
  double psnr, ssim, m_psnr, m_ssim, gaussians;
  // What the removal had to fix (goris eval's "removal" block, on data sets with full_ images): PSNR / SSIM /
  // FLIP inside the changed region, the ghost ratio over it, its floor (stage 1's own distance from the views
  // with the target there, in the same units), and FLIP over the whole image.
  double region_psnr, region_ssim, region_flip, ghost_ratio, ghost_floor, flip, region_fraction;
  // For a removal of an intrinsic run: the share of the glossy surface's colour that stage 1's glossy term
  // carries (goris eval's "reflections" block, train/intrinsic/glossy_share.h).
  double stage1_glossy_share;
  std::string device;  // the device the evaluation rendered on
  Metrics();
};
// Reads RUN/metrics.json; goris::Error naming the file when it is missing or not an object.
Metrics read_metrics(const std::filesystem::path& metrics_json);
// `goris eval RUN --split test --device DEVICE` as a child process (log in `log`); on success `out` holds
// the metrics' means. gt "after" (the test images; after removal for GOR-IS sets) writes RUN/metrics.json,
// gt "full" (GOR-IS test/full_XXX.png: the scene with the target) RUN/metrics_full.json.
StepRun run_eval(const std::filesystem::path& run_dir, const std::string& device, const std::filesystem::path& log,
                 Metrics& out, const std::string& gt = "after");

// Stage-1, fine-tune and distillation iterations of a named schedule: short (500 stage-1 iterations),
// medium (2000), long (8000), full (30000) and the hidden `tiny` of the CLI tests (30, seconds long, with extra options
// that shrink the model). Stage 2 scales with stage 1 like `goris remove` does (4000 at 30K); the
// distillation too (2000 at 30K) but never below 500 iterations.
struct Schedule {
  std::string name;
  int train_iters = 0, remove_iters = 0, export_iters = 0;
  std::vector<std::string> extra_train_args;
};
Schedule schedule_of(const std::string& name);

// Results kept per run in DIR/result.json ({"options": ..., "binary": ..., "row": ...}) so that a rerun with
// the same options reuses them: the row when the file was written with `options` by this very binary
// (binary_fingerprint) and the row's status is "ok". A rebuilt goris recomputes every row: a result made by
// other code is never mixed into a table.
std::string binary_fingerprint();
// any_binary: accept a row written by another build too (reports of results already made, --report-only).
std::optional<nlohmann::json> reusable_row(const std::filesystem::path& dir, const nlohmann::json& options,
                                           bool any_binary = false);
void write_result(const std::filesystem::path& dir, const nlohmann::json& options, const nlohmann::json& row);

// A JSON object read from `path`; goris::Error naming the file when it is missing or not an object.
nlohmann::json read_json_object(const std::filesystem::path& path);
// j[key] when it is a number, else NaN (shared with the user commands).
using cli::json_number;
// Writes text through a temporary file renamed into place.
void write_text(const std::filesystem::path& path, const std::string& text);

// printf-formatted number, "" for NaN / Inf (an empty table cell).
std::string fmt(double v, const char* format);
// A CSV field, quoted when it holds a comma, a quote or a newline.
std::string csv_field(const std::string& s);
// A markdown table cell: '|' escaped, newlines as spaces.
std::string md_cell(std::string s);

}  // namespace goris::bench
