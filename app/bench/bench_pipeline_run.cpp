#include "app/bench/bench_pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "app/cli_common/command.h"
#include "core/io/file_bytes.h"
#include "core/util/error.h"
#include "removal/pipeline/removal_pipeline.h"
#include "tools/synth/synth.h"

namespace goris::bench::pipeline {

namespace {

// A stage-1 run's recorded arguments without its own output folder: a run folder holds no path of its own, so
// a bench folder copied or moved elsewhere keeps its stage-1 runs.
json without_run_folder(json options) {
  if (!options.is_object() || !options.contains("args") || !options["args"].is_array()) return options;
  json& args = options["args"];
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "--out") args[i + 1] = "RUN";
  return options;
}

// DATA/train_after of a synth data set, rendered when it is missing (`goris synth --train-after`).
fs::path true_fill_images(const std::string& data) {
  const fs::path dir = fs::path(data) / "train_after";
  if (fs::is_directory(dir)) return dir;
  std::printf("    synth    the training views of %s without the target\n", data.c_str());
  std::fflush(stdout);
  goris::synth::render_train_after({data, fs::path(GORIS_RESOURCE_DIR) / "synth" / "render_scene.py", {}, {}});
  return dir;
}

}  // namespace

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
  // time, wherever its bench folder was when it trained; --keep-stage1 also takes one another build trained
  // (to measure a change of the removal alone, in a copy of the folder that measured the change's base).
  if (fs::exists(dir / "stage1.json")) {
    const json j = read_json_object(dir / "stage1.json");
    const bool same_binary = j.value("binary", std::string()) == goris::bench::binary_fingerprint();
    if (without_run_folder(j.value("options", json())) == without_run_folder(options) && j.value("ok", false) &&
        (same_binary || o_.keep_stage1)) {
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
  r.ghost_ratio = m.ghost_ratio, r.ghost_floor = m.ghost_floor, r.stage1_glossy_share = m.stage1_glossy_share;
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
      if (c.train_args.empty() || std::string(c.stage1).rfind("auto", 0) == 0)  // what --mode auto decided
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
      if (c.true_fills) rm.insert(rm.end(), {"--fill-truth", true_fill_images(data).string()});
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
  std::map<std::string, std::string> images;                 // suite scenes: scene_images_fingerprint
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
      images[sc.name] = goris::bench::scene_images_fingerprint(dir);
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
  if (!o_.suite.empty()) write_suite(rows, kinds, images);
  int failed = 0;
  for (const Row& r : rows) failed += r.status == "failed";
  std::printf("wrote %s, %s and the charts in %s (%zu rows, %d failed)\n", (out_ / "results.csv").c_str(),
              (out_ / "results.md").c_str(), out_.c_str(), rows.size(), failed);
  if (failed) goris::cli::set_exit_code(1);
}

}  // namespace goris::bench::pipeline
