#include "app/bench/bench_pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/cli_common/command.h"
#include "core/io/file_bytes.h"
#include "core/util/error.h"
#include "removal/pipeline/removal_pipeline.h"
#include "tools/report/chart.h"
#include "tools/report/pareto.h"

namespace goris::bench::pipeline {

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
                    "region_psnr,region_ssim,region_flip,flip,ghost_ratio,ghost_floor,stage1_glossy_share,train_s,select_s,"
                    "remove_s";
  for (const auto& s : steps) csv += "," + step_column(s);
  csv += ",export_s,eval_s,total_s,cpu_s,peak_host_mib,peak_device_mib,reused,error,note\n";
  for (const Row& r : rows) {
    csv += csv_field(r.scene) + "," + csv_field(r.config) + "," + r.schedule + "," + r.status + "," +
           csv_field(r.device) + "," + std::to_string(r.train_iters) + "," + std::to_string(r.remove_iters) + "," +
           fmt(r.gaussians, "%.0f") + "," + fmt(r.psnr, "%.3f") + "," + fmt(r.ssim, "%.4f") + "," +
           fmt(r.m_psnr, "%.3f") + "," + fmt(r.m_ssim, "%.4f") + "," + fmt(r.region_psnr, "%.3f") + "," +
           fmt(r.region_ssim, "%.4f") + "," + fmt(r.region_flip, "%.4f") + "," + fmt(r.flip, "%.4f") + "," +
           fmt(r.ghost_ratio, "%.3f") + "," + fmt(r.ghost_floor, "%.3f") + "," + fmt(r.stage1_glossy_share, "%.3f") + "," +
           fmt(r.train_s, "%.2f") + "," +
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
void Bench::write_suite(const std::vector<Row>& rows, const std::map<std::string, std::string>& kinds,
                        const std::map<std::string, std::string>& images) const {
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
      s.ghost_floor = r.ghost_floor, s.stage1_glossy_share = r.stage1_glossy_share;
      if (images.count(r.scene)) s.scene_images = images.at(r.scene);
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
    // The committed summary is read before --publish may overwrite it (./dev suite fast --publish docs/results
    // checks against the very file it republishes).
    const json committed = o_.check.empty() ? json() : read_json_object(o_.check);
    if (!o_.publish.empty()) publish_suite(results, sched);
    if (o_.check.empty() || committed.value("schedule", "") != sched) continue;
    const auto check = goris::bench::check_suite(committed, sum.json, o_.tolerance_db);
    for (const auto& line : check.not_compared) std::printf("suite check: not compared: %s\n", line.c_str());
    if (check.unverified)
      std::printf("suite check: %d rows compared without knowing whether their scenes rendered alike (the committed "
                  "results name no scene images)\n", check.unverified);
    if (check.compared == 0 && !check.not_compared.empty()) {
      std::printf("\nSUITE CHECK against %s: nothing could be compared - every scene rendered differently from those "
                  "the committed results were measured on (another Blender build or machine). Make a reference on this "
                  "machine: run the committed command with the code that made it, and --check against that.\n",
                  o_.check.c_str());
      goris::cli::set_exit_code(1);
      continue;
    }
    if (check.regressions.empty()) {
      std::printf("suite check against %s: no regression in %d rows (tolerance %.2f dB)\n", o_.check.c_str(),
                  check.compared, o_.tolerance_db);
      continue;
    }
    std::printf("\nSUITE REGRESSION against %s (tolerance %.2f dB):\n", o_.check.c_str(), o_.tolerance_db);
    for (const auto& b : check.regressions) std::printf("  %s\n", b.c_str());
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

}  // namespace goris::bench::pipeline
