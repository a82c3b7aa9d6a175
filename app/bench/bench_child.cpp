#include "app/bench/bench_child.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>

#include "app/cli_common/command.h"
#include "app/cli_common/stop_signals.h"
#include "core/io/file_bytes.h"
#include "core/io/json_file.h"
#include "core/util/error.h"
#include "core/util/fnv1a.h"

extern char** environ;

namespace goris::bench {

CLI::App& bench_group(CLI::App& root) {
  return goris::cli::subcommand_group(root, "bench", "Benchmarks (medians, with the machine and sizes)");
}

namespace fs = std::filesystem;
using nlohmann::json;

std::string failure_message(const fs::path& log) {
  std::string text;
  try {
    text = read_text_file(log);
  } catch (const Error&) {
    return "";
  }
  std::istringstream in(text);
  std::string line, last, err;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t cr = line.rfind('\r');  // progress bars redraw with \r
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (line.empty()) continue;
    last = line;
    if (line.rfind("error:", 0) == 0) err = line;
  }
  return err.empty() ? last : err;
}

namespace {

// This process's environment with NAME set to value (replacing an inherited NAME).
std::vector<std::string> environment_with(const std::string& name, const std::string& value) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind(name + "=", 0) != 0) env.emplace_back(*e);
  env.push_back(name + "=" + value);
  return env;
}

}  // namespace

StepRun run_child(const std::string& step, std::vector<std::string> args, const fs::path& log) {
  std::printf("    %-8s goris", step.c_str());
  for (const auto& a : args) std::printf(" %s", a.c_str());
  std::printf("\n");
  std::fflush(stdout);
  // Spawning /proc/self/exe runs this very binary even if a rebuild replaced the file during a long bench.
  const std::string exe = "/proc/self/exe";
  args.insert(args.begin(), fs::read_symlink(exe).string());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The child writes its peak CUDA memory beside the log at exit (core/compute/memory.h).
  fs::path memory_report = log;
  memory_report.replace_extension(".device_memory.json");
  std::error_code ec;
  fs::remove(memory_report, ec);
  std::vector<std::string> env_vars = environment_with("GORIS_DEVICE_MEMORY_REPORT", memory_report.string());
  std::vector<char*> envp;
  for (auto& e : env_vars) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  StepRun r;
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    r.error = step + ": could not start " + exe;
    return r;
  }
  int status = 0;
  struct rusage ru {};
  int stopped_by = 0;
  {
    // A stop signal sent to the bench alone (kill, timeout, a cancelled job) is passed on to the child, which
    // checkpoints and exits; then the bench stops with the status for that signal.
    const cli::StopSignals stop;
    while (wait4(pid, &status, WNOHANG, &ru) == 0) {
      if (stop.signal() && !stopped_by) {
        stopped_by = stop.signal();
        kill(pid, stopped_by);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!stopped_by) stopped_by = stop.signal();
  }
  if (stopped_by) {
    std::printf("    %-8s interrupted (%s): stopping the bench [log %s]\n", step.c_str(),
                cli::stop_signal_name(stopped_by).c_str(), log.string().c_str());
    std::fflush(stdout);
    std::exit(128 + stopped_by);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.peak_mib = double(ru.ru_maxrss) / 1024.0;  // Linux: KiB
  r.cpu_seconds = double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (fs::exists(memory_report)) {
    try {
      r.peak_device_mib = json_number(read_json_object(memory_report), "peak_device_memory_bytes") / 1048576.0;
    } catch (const Error&) {
    }  // a child killed while writing leaves no usable report: the peak stays unknown
  }
  if (!r.ok) {
    const std::string how = WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                              : "killed by signal " + std::to_string(WTERMSIG(status));
    const std::string msg = failure_message(log);
    r.error = step + " failed (" + how + ")" + (msg.empty() ? "" : ": " + msg) + " [log " + log.string() + "]";
    std::printf("    %-8s FAILED: %s\n", step.c_str(), r.error.c_str());
  } else {
    if (r.peak_device_mib > 0)
      std::printf("    %-8s %.1f s, peak %.0f MiB host, %.0f MiB device\n", step.c_str(), r.seconds, r.peak_mib,
                  r.peak_device_mib);
    else
      std::printf("    %-8s %.1f s, peak %.0f MiB\n", step.c_str(), r.seconds, r.peak_mib);
  }
  std::fflush(stdout);
  return r;
}

Metrics::Metrics()
    : psnr(std::nan("")), ssim(std::nan("")), m_psnr(std::nan("")), m_ssim(std::nan("")), gaussians(std::nan("")),
      region_psnr(std::nan("")), region_ssim(std::nan("")), region_flip(std::nan("")), ghost_ratio(std::nan("")),
      ghost_floor(std::nan("")), flip(std::nan("")), region_fraction(std::nan("")), stage1_glossy_share(std::nan("")) {}

Metrics read_metrics(const fs::path& metrics_json) {
  const json j = read_json_object(metrics_json);
  Metrics m;
  m.psnr = json_number(j, "psnr"), m.ssim = json_number(j, "ssim"), m.gaussians = json_number(j, "gaussians");
  if (j.contains("masked")) m.m_psnr = json_number(j["masked"], "psnr"), m.m_ssim = json_number(j["masked"], "ssim");
  m.device = j.value("device", std::string());
  m.flip = json_number(j, "flip");
  if (j.contains("removal")) {
    const json& r = j["removal"];
    m.region_psnr = json_number(r, "region_psnr"), m.region_ssim = json_number(r, "region_ssim");
    m.region_flip = json_number(r, "region_flip"), m.ghost_ratio = json_number(r, "ghost_ratio");
    m.region_fraction = json_number(r, "region_fraction"), m.ghost_floor = json_number(r, "ghost_floor");
  }
  if (j.contains("reflections")) m.stage1_glossy_share = json_number(j["reflections"], "stage1_glossy_share");
  return m;
}

StepRun run_eval(const fs::path& run_dir, const std::string& device, const fs::path& log, Metrics& out,
                 const std::string& gt) {
  const fs::path metrics = run_dir / (gt == "after" ? "metrics.json" : "metrics_" + gt + ".json");
  StepRun r = run_child("eval", {"eval", run_dir.string(), "--split", "test", "--gt", gt, "--out", metrics.string(),
                                 "--device", device},
                        log);
  if (r.ok) out = read_metrics(metrics);
  return r;
}

Schedule schedule_of(const std::string& name) {
  if (name == "tiny")
    return {name, 30, 10, 10,
            {"--resolution", "64", "--init-points", "3000", "--set", "intrinsic_env_resolution=8", "--set",
             "random_init_box_ratio=0.15"}};
  const int iters = name == "short" ? 500 : name == "medium" ? 2000 : name == "long" ? 8000 : 30000;
  // The distillation fits SH to the shaded renders from scratch, so it needs a few hundred iterations even
  // after a short stage 1 (a hundred-odd iterations left the baked model far from the renders it copies).
  return {name, iters, std::max(10, iters * 4000 / 30000), std::min(2000, std::max(500, iters * 2000 / 30000)), {}};
}

std::string binary_fingerprint() {
  static const std::string fp = [] {
    const std::vector<uint8_t> b = read_file_bytes("/proc/self/exe");
    return std::to_string(fnv1a(std::string_view(reinterpret_cast<const char*>(b.data()), b.size())));
  }();
  return fp;
}

std::optional<json> reusable_row(const fs::path& dir, const json& options, bool any_binary) {
  if (!fs::exists(dir / "result.json")) return std::nullopt;
  const json j = read_json_object(dir / "result.json");
  if (j.value("options", json()) != options || (!any_binary && j.value("binary", std::string()) != binary_fingerprint()) ||
      j.value("row", json()).value("status", "") != "ok")
    return std::nullopt;
  return j["row"];
}

void write_result(const fs::path& dir, const json& options, const json& row) {
  write_json_file(dir / "result.json", {{"options", options}, {"binary", binary_fingerprint()}, {"row", row}});
}

json read_json_object(const fs::path& path) {
  const json j = json::parse(read_text_file(path), nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw Error(path.string(), "not a JSON object");
  return j;
}

void write_text(const fs::path& path, const std::string& text) { write_file_bytes(path, text.data(), text.size()); }

std::string fmt(double v, const char* format) {
  if (!std::isfinite(v)) return "";
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string md_cell(std::string s) {
  for (size_t p = 0; (p = s.find('|', p)) != std::string::npos; p += 2) s.replace(p, 1, "\\|");
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

}  // namespace goris::bench
