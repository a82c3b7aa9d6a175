// `goris bench stability --out DIR [--cases all|NAME,...] [--schedule short|medium] [--device D]`: the
// method's known failure cases end to end (train, eval of stage 1 against the views with the target,
// select --masks, remove, eval against the after-removal ground truth; the single-view case, which has no
// masks to select with, stage 1 only), each step a `goris` child process, so a crash is a recorded failure
// and the bench goes on. Per case: whether it finished, whether every output is finite (checkpoints with
// Adam moments, PLYs, environment map and roughness net, rendered test images, metrics), PSNR / SSIM /
// M-PSNR / M-SSIM, times, NaN-recovery events (training steps the trainer skipped for non-finite values),
// and how much it degrades against its reference case. Writes results.csv and results.md; a case whose
// result.json in DIR was made with the same options is reused.
// Exits 1 when a case crashed or produced a non-finite output; poor metrics are reported, not failures.
//
// Scenes: the generated ones (`goris synth`, rendered once into DIR/scenes and reused) and lambert_room /
// twin_mirrors of the shared data sets (--datasets).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/bench_child.h"
#include "app/cli_common/command.h"
#include "core/io/file_bytes.h"
#include "core/io/json_file.h"
#include "core/util/error.h"
#include "train/config/train_config.h"
#include "train/setup/finite_outputs.h"

namespace {
namespace fs = std::filesystem;
using goris::Error;
using nlohmann::json;
using namespace goris::bench;
using goris::write_json_file;

// Generated scenes: 128 px like the schedules' training resolution, few views and samples to keep the
// bench short on a CPU (Cycles noise stays below what 500 iterations resolve).
constexpr int kSynthRes = 128, kSynthSpp = 16, kSynthTrain = 24, kSynthTest = 8, kSynthSeed = 1;
constexpr int kTrainResolution = 128;  // unless the schedule sets one (tiny)
// A case "degrades" when it loses this much against its reference: well above the run-to-run spread of
// 500-iteration runs.
constexpr double kDegradedPsnr = 0.5, kDegradedMaskedPsnr = 1.0;

struct SceneSpec {
  const char* key;
  const char* preset;      // goris synth preset; "" = the shared data set `key`
  double table_roughness;  // < 0: the preset's own
  const char* description;
};

const std::vector<SceneSpec>& scenes() {
  static const std::vector<SceneSpec> s = {
      {"glossy_table", "glossy-table", -1, "generated glossy-table scene (seed 1)"},
      {"glossy_table_r0", "glossy-table", 0.0, "the glossy-table scene with table roughness 0.0 (a mirror)"},
      {"glossy_table_r1", "glossy-table", 1.0, "the glossy-table scene with table roughness 1.0"},
      {"occluded", "occluded", -1, "generated occluded scene (the target behind a block in most views)"},
      {"lambert_room", "", -1, "shared data set: diffuse only, shadows and colour bleeding"},
      {"twin_mirrors", "", -1, "shared data set: a steel table and a mirror facing it"},
  };
  return s;
}

const SceneSpec& scene_spec(const std::string& key) {
  return *std::find_if(scenes().begin(), scenes().end(), [&](const SceneSpec& s) { return s.key == key; });
}

struct CaseSpec {
  std::string name, scene;
  std::string reference;  // the case it is compared with; "" = a reference itself
  std::string mode;       // radiance | intrinsic
  std::vector<std::string> sets;
  bool normal_prior = false;  // --normals SCENE/train/gt
  bool stage1_only = false;  // no selection, no removal: stage 1 scored against the scene with the target
  std::string ablate;  // goris remove --ablate
  std::string description;
};

std::string number_text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

const std::vector<CaseSpec>& cases() {
  static const std::vector<CaseSpec> c = [] {
    const goris::IntrinsicSettings d = goris::TrainConfig{}.intrinsic;
    std::vector<CaseSpec> v;
    v.push_back({"reference", "glossy_table", "", "intrinsic", {}, true, false, "",
                 "glossy table, intrinsic stage 1 with the normal prior, loss weights x1"});
    // The paper (S1.5) scales the non-Lambertian losses L_n and L_s together: stable in [x0.5, x5],
    // artefacts at <= x0.2.
    for (double k : {0.2, 0.5, 2.0, 5.0})
      v.push_back({"weights_x" + number_text(k), "glossy_table", "reference", "intrinsic",
                   {"intrinsic_normal_prior=" + number_text(d.normal_prior * k),
                    "intrinsic_normal_prior_final=" + number_text(d.normal_prior_final * k),
                    "intrinsic_smoothness=" + number_text(d.smoothness * k)},
                   true, false, "", "normal-prior and smoothness loss weights x" + number_text(k)});
    v.push_back({"no_normal_prior", "glossy_table", "reference", "intrinsic", {}, false, false, "",
                 "no normal prior"});
    v.push_back({"no_glossy_mask", "glossy_table", "reference", "intrinsic", {"use_glossy_masks=false"}, true,
                 false, "", "intrinsic mode without the glossy masks (the region loss has no target)"});
    // Without object masks the target cannot be selected by masks, and a click on it in the only view picks a
    // floater in front of the camera (at 500 iterations the hull of the grown pick is the whole scene): the
    // case checks that single-view training stays finite and how far its novel views fall behind.
    v.push_back({"single_view", "glossy_table", "reference", "intrinsic",
                 {"max_train_views=1", "use_object_masks=false"}, true, true, "",
                 "one training view, target unmasked: stage 1 only, scored against the test views with the "
                 "target (nothing selectable to remove)"});
    v.push_back({"roughness_0", "glossy_table_r0", "reference", "intrinsic", {}, true, false, "",
                 "table roughness 0.0 (a perfect mirror; the reference's scene differs only in that roughness)"});
    v.push_back({"roughness_1", "glossy_table_r1", "reference", "intrinsic", {}, true, false, "",
                 "table roughness 1.0 (the reference's scene differs only in that roughness)"});
    for (const char* s : {"lambert_room", "twin_mirrors", "occluded"}) {
      v.push_back({std::string(s) + "_baseline", s, "", "radiance", {}, false, false, "material,lamask",
                   "radiance stage 1 and RGB inpainting (the reference of " + std::string(s) + ")"});
      v.push_back({s, s, std::string(s) + "_baseline", "intrinsic", {}, false, false, "",
                   "the full method (intrinsic, material inpainting, lighting-aware mask)"});
    }
    return v;
  }();
  return c;
}

const CaseSpec* find_case(const std::string& name) {
  for (const auto& c : cases())
    if (c.name == name) return &c;
  return nullptr;
}

struct Options {
  std::string out, cases = "all", schedule = "short", device = "auto", glossy_data;
  std::string datasets = std::string(GORIS_RESOURCE_DIR) + "/../../shared/datasets";
};

// A scene ready to train on, or why it is not.
struct SceneData {
  fs::path data;
  json options;  // what made it (for reusing results)
  std::string error;
  bool has_normals = false;  // train/gt/normal_*.exr (the scene generator's ground truth)
};

bool has_normal_maps(const fs::path& data) {
  const fs::path gt = data / "train" / "gt";
  if (!fs::is_directory(gt)) return false;
  for (const auto& e : fs::directory_iterator(gt)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("normal_", 0) == 0 && e.path().extension() == ".exr") return true;
  }
  return false;
}

// Training steps skipped for non-finite values, from a step's log ("warning: iteration N: ...; step
// skipped, ..."): how many, and the first message.
void count_skips(const fs::path& log, int& count, std::string& first) {
  if (!fs::exists(log)) return;
  std::istringstream in(goris::read_text_file(log));
  for (std::string line; std::getline(in, line);) {
    const size_t cr = line.rfind('\r');  // progress bars redraw with \r
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (line.rfind("warning:", 0) == 0 && line.find("step skipped") != std::string::npos) {
      if (count++ == 0) first = line;
    }
  }
}

struct Row {
  std::string name, scene, reference, status = "failed", error, device, note;  // note: "a; b; c"
  std::vector<std::string> problems;  // non-finite outputs
  bool reused = false, finished = false, checked = false;
  int nan_skips = 0, train_iters = 0;
  std::string first_skip;
  double gaussians = std::nan(""), psnr = std::nan(""), ssim = std::nan(""), m_psnr = std::nan(""),
         m_ssim = std::nan("");
  double s1_psnr = std::nan(""), s1_ssim = std::nan("");  // stage 1 against the test views with the target
  double train_s = 0, select_s = 0, remove_s = 0, eval_s = 0, peak_mib = 0;
  double total_s() const { return train_s + select_s + remove_s; }
  bool finite() const { return problems.empty(); }
};

json row_json(const Row& r) {
  return {{"name", r.name},         {"scene", r.scene},         {"reference", r.reference},
          {"status", r.status},     {"error", r.error},         {"device", r.device},
          {"note", r.note},         {"problems", r.problems},   {"finished", r.finished},
          {"checked", r.checked},   {"nan_skips", r.nan_skips}, {"first_skip", r.first_skip},
          {"train_iters", r.train_iters}, {"gaussians", r.gaussians}, {"psnr", r.psnr},
          {"ssim", r.ssim},         {"m_psnr", r.m_psnr},       {"m_ssim", r.m_ssim},
          {"s1_psnr", r.s1_psnr},   {"s1_ssim", r.s1_ssim},
          {"train_s", r.train_s},   {"select_s", r.select_s},   {"remove_s", r.remove_s},
          {"eval_s", r.eval_s},     {"peak_mib", r.peak_mib}};
}

Row row_from_json(const json& j) {
  Row r;
  auto s = [&](const char* k) { return j.value(k, std::string()); };
  r.name = s("name"), r.scene = s("scene"), r.reference = s("reference"), r.status = s("status");
  r.error = s("error"), r.device = s("device"), r.note = s("note"), r.first_skip = s("first_skip");
  if (j.contains("problems") && j["problems"].is_array())
    for (const auto& p : j["problems"]) r.problems.push_back(p.is_string() ? p.get<std::string>() : p.dump());
  r.finished = j.value("finished", false), r.checked = j.value("checked", false);
  r.nan_skips = j.value("nan_skips", 0), r.train_iters = j.value("train_iters", 0);
  r.gaussians = json_number(j, "gaussians"), r.psnr = json_number(j, "psnr"), r.ssim = json_number(j, "ssim");
  r.m_psnr = json_number(j, "m_psnr"), r.m_ssim = json_number(j, "m_ssim");
  r.s1_psnr = json_number(j, "s1_psnr"), r.s1_ssim = json_number(j, "s1_ssim");
  r.train_s = json_number(j, "train_s"), r.select_s = json_number(j, "select_s");
  r.remove_s = json_number(j, "remove_s"), r.eval_s = json_number(j, "eval_s"), r.peak_mib = json_number(j, "peak_mib");
  return r;
}

// Differences against the reference case (NaN when either side has no number).
struct Delta {
  const Row* ref = nullptr;
  double psnr = std::nan(""), ssim = std::nan(""), m_psnr = std::nan(""), m_ssim = std::nan(""),
         s1_psnr = std::nan(""), time_ratio = std::nan("");
  bool degraded() const {
    return psnr <= -kDegradedPsnr || m_psnr <= -kDegradedMaskedPsnr || s1_psnr <= -kDegradedPsnr;
  }
};

Delta delta_of(const Row& r, const std::vector<Row>& rows) {
  Delta d;
  if (r.reference.empty()) return d;
  for (const Row& x : rows)
    if (x.name == r.reference) d.ref = &x;
  if (!d.ref || r.status != "ok" || d.ref->status != "ok") return d;
  d.psnr = r.psnr - d.ref->psnr, d.ssim = r.ssim - d.ref->ssim;
  d.m_psnr = r.m_psnr - d.ref->m_psnr, d.m_ssim = r.m_ssim - d.ref->m_ssim;
  d.s1_psnr = r.s1_psnr - d.ref->s1_psnr;
  if (d.ref->total_s() > 0) d.time_ratio = r.total_s() / d.ref->total_s();
  return d;
}

std::string verdict(const Row& r, const Delta& d) {
  if (r.status != "ok") return r.status;
  if (r.reference.empty()) return "reference";
  if (!std::isfinite(d.psnr) && !std::isfinite(d.s1_psnr)) return "no reference result";
  return d.degraded() ? "degrades" : "stable";
}

std::string signed_fmt(double v, const char* f) {
  const std::string s = fmt(v, f);
  return s.empty() || v < 0 ? s : "+" + s;
}

void add_note(Row& r, const std::string& text) { r.note += (r.note.empty() ? "" : "; ") + text; }

class Bench {
 public:
  explicit Bench(const Options& o) : o_(o), out_(fs::absolute(o.out)), sched_(schedule_of(o.schedule)) {}
  void run();

 private:
  const SceneData& scene(const std::string& key);
  Row run_case(const CaseSpec& c);
  void check_outputs(Row& r, const fs::path& run, const fs::path& logs) const;
  void evaluate_stage1(Row& r, const fs::path& run, const fs::path& logs) const;
  void write_outputs(const std::vector<Row>& rows, const std::vector<const CaseSpec*>& plan) const;
  int train_resolution() const;

  Options o_;
  fs::path out_;
  Schedule sched_;
  std::map<std::string, SceneData> scenes_;
};

int Bench::train_resolution() const {
  const auto& a = sched_.extra_train_args;
  const auto it = std::find(a.begin(), a.end(), "--resolution");
  return it != a.end() && it + 1 != a.end() ? std::stoi(*(it + 1)) : kTrainResolution;
}

const SceneData& Bench::scene(const std::string& key) {
  if (auto it = scenes_.find(key); it != scenes_.end()) return it->second;
  const SceneSpec& spec = scene_spec(key);
  SceneData sd;
  if (key == "glossy_table" && !o_.glossy_data.empty()) {
    sd.data = fs::weakly_canonical(fs::absolute(o_.glossy_data));
    sd.options = {{"data", sd.data.string()}};
  } else if (!*spec.preset) {
    sd.data = fs::weakly_canonical(fs::absolute(fs::path(o_.datasets) / key));
    sd.options = {{"data", sd.data.string()}};
  } else {
    // Generated once into DIR/scenes/KEY; DIR/scenes/KEY.json records the arguments that made it.
    const fs::path dir = out_ / "scenes" / key, marker = out_ / "scenes" / (std::string(key) + ".json");
    std::vector<std::string> args = {"synth", "--preset", spec.preset, "--res", std::to_string(kSynthRes),
                                     "--spp", std::to_string(kSynthSpp), "--train", std::to_string(kSynthTrain),
                                     "--test", std::to_string(kSynthTest), "--seed", std::to_string(kSynthSeed),
                                     "--out", dir.string()};
    if (spec.table_roughness >= 0) args.insert(args.end(), {"--table-roughness", number_text(spec.table_roughness)});
    sd.data = dir;
    sd.options = {{"synth", args}};
    bool reuse = false;
    if (fs::exists(marker) && fs::is_directory(dir)) {
      const json j = read_json_object(marker);
      reuse = j.value("args", json()) == json(args) && j.value("ok", false);
    }
    if (reuse) {
      std::printf("  scene %s: reused %s\n", key.c_str(), dir.c_str());
    } else {
      std::printf("  scene %s: %s\n", key.c_str(), spec.description);
      fs::create_directories(out_ / "scenes");
      const StepRun s = run_child("synth", args, out_ / "scenes" / (std::string(key) + ".log"));
      write_json_file(marker, {{"args", args}, {"ok", s.ok}, {"seconds", s.seconds}, {"error", s.error}});
      if (!s.ok) sd.error = s.error;
    }
  }
  if (sd.error.empty() && !fs::is_directory(sd.data)) sd.error = sd.data.string() + ": no such data set folder";
  sd.has_normals = sd.error.empty() && has_normal_maps(sd.data);
  return scenes_[key] = sd;
}

// Finite checks of whatever the stage-1 run and the removal hold, and the skipped steps in the logs.
void Bench::check_outputs(Row& r, const fs::path& run, const fs::path& logs) const {
  for (const fs::path& dir : {run, run / "removal"}) {
    if (!fs::is_directory(dir)) continue;
    const goris::RunFiniteReport f = goris::check_run_finite(dir);
    r.checked = r.checked || !f.checked.empty();
    r.problems.insert(r.problems.end(), f.problems.begin(), f.problems.end());
  }
  for (const char* step : {"train", "remove"})
    count_skips(logs / (std::string(step) + ".log"), r.nan_skips, r.first_skip);
}

// Stage 1 against the test views with the target (test/full_XXX.png): the reconstruction before anything is
// removed, which every case has (the single-view case has nothing else).
void Bench::evaluate_stage1(Row& r, const fs::path& run, const fs::path& logs) const {
  Metrics m;
  const StepRun ev = run_eval(run, o_.device, logs / "eval_stage1.log", m, "full");
  r.eval_s += ev.seconds, r.peak_mib = std::max(r.peak_mib, ev.peak_mib);
  if (!ev.ok) throw Error(ev.error);
  r.s1_psnr = m.psnr, r.s1_ssim = m.ssim;
  if (!std::isfinite(r.gaussians)) r.gaussians = m.gaussians;
  if (!m.device.empty()) r.device = m.device;
}

std::string result_text(const Row& r) {
  std::string t = r.status;
  if (std::isfinite(r.psnr)) t += ", PSNR after removal " + fmt(r.psnr, "%.2f") + " dB";
  if (std::isfinite(r.s1_psnr)) t += ", stage 1 with the target " + fmt(r.s1_psnr, "%.2f") + " dB";
  return t;
}

Row Bench::run_case(const CaseSpec& c) {
  Row r;
  r.name = c.name, r.scene = c.scene, r.reference = c.reference, r.train_iters = sched_.train_iters;
  r.device = o_.device;
  const fs::path dir = out_ / "runs" / c.name, logs = dir / "logs", run = dir / "run";
  const SceneData& sd = scene(c.scene);

  std::vector<std::string> train = {"train", sd.data.string(), "--out", run.string(), "--iters",
                                    std::to_string(sched_.train_iters), "--device", o_.device,
                                    "--checkpoint-every", "0", "--mode", c.mode};
  if (c.normal_prior && sd.has_normals) train.insert(train.end(), {"--normals", (sd.data / "train" / "gt").string()});
  else if (c.normal_prior && sd.error.empty()) add_note(r, "no normal prior: the scene has no train/gt/normal_*.exr");
  for (const auto& s : c.sets) train.insert(train.end(), {"--set", s});
  if (std::find(sched_.extra_train_args.begin(), sched_.extra_train_args.end(), "--resolution") ==
      sched_.extra_train_args.end())
    train.insert(train.end(), {"--resolution", std::to_string(kTrainResolution)});
  train.insert(train.end(), sched_.extra_train_args.begin(), sched_.extra_train_args.end());
  std::vector<std::string> remove = {"remove", run.string(), "--iters", std::to_string(sched_.remove_iters),
                                     "--device", o_.device};
  if (!c.ablate.empty()) remove.insert(remove.end(), {"--ablate", c.ablate});
  const json options = {{"scene", sd.options},
                        {"schedule", sched_.name},
                        {"train", train},
                        {"remove", c.stage1_only ? json() : json(remove)},
                        {"select", c.stage1_only ? "none (stage 1 only)" : "masks"},
                        {"device", o_.device}};

  if (const auto row = reusable_row(dir, options)) {
    Row old = row_from_json(*row);
    old.reused = true;
    if (!std::isfinite(old.s1_psnr)) {  // a result from before the stage-1 score: add it
      try {
        evaluate_stage1(old, run, logs);
        old.problems = goris::metrics_finite_problems(run / "metrics_full.json");
        if (!old.finite()) old.status = "non-finite";
        write_result(dir, options, row_json(old));
      } catch (const std::exception& e) {
        add_note(old, std::string("no stage-1 score: ") + e.what());
      }
    }
    std::printf("  %s: reused the result in %s (%s)\n", c.name.c_str(), dir.c_str(), result_text(old).c_str());
    return old;
  }
  std::printf("  %s (%s): %s\n", c.name.c_str(), c.scene.c_str(), c.description.c_str());
  fs::remove_all(dir);
  fs::create_directories(logs);
  try {
    if (!sd.error.empty()) throw Error("scene " + c.scene + ": " + sd.error);
    const StepRun tr = run_child("train", train, logs / "train.log");
    r.train_s = tr.seconds, r.peak_mib = tr.peak_mib;
    if (!tr.ok) throw Error(tr.error);
    evaluate_stage1(r, run, logs);
    if (!c.stage1_only) {
      const StepRun sel = run_child("select", {"select", run.string(), "--masks", "--device", o_.device},
                                    logs / "select.log");
      r.select_s = sel.seconds, r.peak_mib = std::max(r.peak_mib, sel.peak_mib);
      if (!sel.ok) throw Error(sel.error);
      const StepRun rem = run_child("remove", remove, logs / "remove.log");
      r.remove_s = rem.seconds, r.peak_mib = std::max(r.peak_mib, rem.peak_mib);
      if (!rem.ok) throw Error(rem.error);
      Metrics m;
      const StepRun ev = run_eval(run / "removal", o_.device, logs / "eval.log", m);
      r.eval_s += ev.seconds, r.peak_mib = std::max(r.peak_mib, ev.peak_mib);
      if (!ev.ok) throw Error(ev.error);
      r.psnr = m.psnr, r.ssim = m.ssim, r.m_psnr = m.m_psnr, r.m_ssim = m.m_ssim, r.gaussians = m.gaussians;
    }
    r.finished = true;
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  check_outputs(r, run, logs);
  r.status = !r.finite() ? "non-finite" : r.finished ? "ok" : "failed";
  if (r.nan_skips > 0) add_note(r, std::to_string(r.nan_skips) + " training step(s) skipped for non-finite values");
  std::printf("  %s: %s\n", c.name.c_str(), result_text(r).c_str());
  write_result(dir, options, row_json(r));
  return r;
}

void Bench::write_outputs(const std::vector<Row>& rows, const std::vector<const CaseSpec*>& plan) const {
  std::string csv = "case,scene,reference,status,finished,finite,nan_skips,device,train_iters,gaussians,psnr,ssim,"
                    "m_psnr,m_ssim,d_psnr,d_ssim,d_m_psnr,d_m_ssim,verdict,s1_psnr,s1_ssim,d_s1_psnr,train_s,select_s,"
                    "remove_s,eval_s,total_s,time_ratio,peak_host_mib,reused,problems,error,note\n";
  for (const Row& r : rows) {
    const Delta d = delta_of(r, rows);
    std::string problems;
    for (const auto& p : r.problems) problems += (problems.empty() ? "" : "; ") + p;
    csv += r.name + "," + r.scene + "," + r.reference + "," + r.status + "," + (r.finished ? "yes" : "no") + "," +
           (!r.finite() ? "no" : r.checked ? "yes" : "-") + "," + std::to_string(r.nan_skips) + "," +
           csv_field(r.device) + "," + std::to_string(r.train_iters) + "," + fmt(r.gaussians, "%.0f") + "," +
           fmt(r.psnr, "%.3f") + "," + fmt(r.ssim, "%.4f") + "," + fmt(r.m_psnr, "%.3f") + "," +
           fmt(r.m_ssim, "%.4f") + "," + fmt(d.psnr, "%.3f") + "," + fmt(d.ssim, "%.4f") + "," +
           fmt(d.m_psnr, "%.3f") + "," + fmt(d.m_ssim, "%.4f") + "," + verdict(r, d) + "," +
           fmt(r.s1_psnr, "%.3f") + "," + fmt(r.s1_ssim, "%.4f") + "," + fmt(d.s1_psnr, "%.3f") + "," +
           fmt(r.train_s, "%.2f") + "," + fmt(r.select_s, "%.2f") + "," + fmt(r.remove_s, "%.2f") + "," +
           fmt(r.eval_s, "%.2f") + "," + fmt(r.total_s(), "%.2f") + "," + fmt(d.time_ratio, "%.2f") + "," +
           fmt(r.peak_mib, "%.0f") + "," + (r.reused ? "yes" : "no") + "," + csv_field(problems) + "," +
           csv_field(r.error) + "," + csv_field(r.note) + "\n";
  }
  write_text(out_ / "results.csv", csv);

  std::string md = "# GOR-IS stability bench\n\n";
  md += "Schedule `" + sched_.name + "`: " + std::to_string(sched_.train_iters) + " stage-1 iterations, " +
        std::to_string(sched_.remove_iters) + " fine-tune iterations, training at " +
        std::to_string(train_resolution()) + " px; device requested `" + o_.device + "`. Each case runs train, " +
        "eval of stage 1, select (object masks), remove and eval (test views against the after-removal "
        "ground truth; M-PSNR / M-SSIM inside the target's region). *Finite*: every parameter of the final "
        "checkpoints (with Adam moments), both PLYs, the environment map and roughness net, the rendered test "
        "images and the metrics. *NaN skips*: training steps skipped for non-finite values (the trainer's "
        "recovery). *Stage-1 PSNR*: the stage-1 model against the test views with the target (full_XXX.png), "
        "before anything is removed. Δ = case - its reference (same scene unless said); *degrades* = ΔPSNR or "
        "Δ stage-1 PSNR <= -" + fmt(kDegradedPsnr, "%.1f") + " dB, or ΔM-PSNR <= -" +
        fmt(kDegradedMaskedPsnr, "%.1f") + " dB. Times in seconds: total = train + select + remove.\n\n";
  md += "Cases:\n\n";
  for (const CaseSpec* c : plan)
    md += "- `" + c->name + "` (" + c->scene + (c->reference.empty() ? "" : ", vs `" + c->reference + "`") + "): " +
          md_cell(c->description) + "\n";
  md += "\n| case | scene | status | finite | NaN skips | PSNR | SSIM | M-PSNR | M-SSIM | stage-1 PSNR | vs | ΔPSNR "
        "| ΔM-PSNR | Δ stage-1 PSNR | verdict | total s | time vs ref |\n";
  md += "|---|---|---|---|--:|--:|--:|--:|--:|--:|---|--:|--:|--:|---|--:|--:|\n";
  for (const Row& r : rows) {
    const Delta d = delta_of(r, rows);
    md += "| " + r.name + " | " + r.scene + " | " + r.status + (r.reused ? " (reused)" : "") + " | " +
          (!r.finite() ? "**no**" : r.checked ? "yes" : "-") + " | " + std::to_string(r.nan_skips) + " | " +
          fmt(r.psnr, "%.2f") + " | " + fmt(r.ssim, "%.4f") + " | " + fmt(r.m_psnr, "%.2f") + " | " +
          fmt(r.m_ssim, "%.4f") + " | " + fmt(r.s1_psnr, "%.2f") + " | " + r.reference + " | " +
          signed_fmt(d.psnr, "%.2f") + " | " + signed_fmt(d.m_psnr, "%.2f") + " | " + signed_fmt(d.s1_psnr, "%.2f") +
          " | " + verdict(r, d) + " | " + fmt(r.total_s(), "%.1f") + " | " +
          (std::isfinite(d.time_ratio) ? fmt(d.time_ratio, "%.2f") + "x" : "") + " |\n";
  }
  std::vector<std::pair<double, std::string>> degraded;  // (worst PSNR difference, line)
  for (const Row& r : rows) {
    const Delta d = delta_of(r, rows);
    if (!d.degraded()) continue;
    std::string line = "- `" + r.name + "` against `" + r.reference + "`:";
    if (std::isfinite(d.psnr))
      line += " " + signed_fmt(d.psnr, "%.2f") + " dB PSNR, " + signed_fmt(d.m_psnr, "%.2f") + " dB M-PSNR,";
    line += " " + signed_fmt(d.s1_psnr, "%.2f") + " dB stage-1 PSNR\n";
    degraded.push_back({std::min(std::isfinite(d.psnr) ? d.psnr : 0.0, std::isfinite(d.s1_psnr) ? d.s1_psnr : 0.0),
                        line});
  }
  std::sort(degraded.begin(), degraded.end());
  md += "\nDegrading cases (worst first): " + std::string(degraded.empty() ? "none.\n" : "\n\n");
  for (const auto& [v, line] : degraded) md += line;
  std::string notes;
  for (const Row& r : rows) {
    if (!r.error.empty()) notes += "- `" + r.name + "`: **failed**: " + md_cell(r.error) + "\n";
    for (const auto& p : r.problems) notes += "- `" + r.name + "`: **not finite**: " + md_cell(p) + "\n";
    if (!r.first_skip.empty()) notes += "- `" + r.name + "`: first skipped step: " + md_cell(r.first_skip) + "\n";
    if (!r.note.empty()) notes += "- `" + r.name + "`: " + md_cell(r.note) + "\n";
  }
  if (!notes.empty()) md += "\nNotes:\n\n" + notes;
  write_text(out_ / "results.md", md);
}

void Bench::run() {
  // The cases asked for, each with its reference, in the bench's order.
  std::vector<std::string> names;
  std::stringstream ss(o_.cases);
  for (std::string n; std::getline(ss, n, ',');) {
    if (n.empty()) continue;
    if (n == "all") {
      for (const auto& c : cases()) names.push_back(c.name);
      continue;
    }
    const CaseSpec* c = find_case(n);
    if (!c) {
      std::string list;
      for (const auto& k : cases()) list += (list.empty() ? "" : ", ") + k.name;
      throw Error("--cases", "unknown case '" + n + "' (" + list + ", all)");
    }
    names.push_back(n);
    if (!c->reference.empty()) names.push_back(c->reference);
  }
  std::vector<const CaseSpec*> plan;
  for (const auto& c : cases())
    if (std::find(names.begin(), names.end(), c.name) != names.end()) plan.push_back(&c);
  if (plan.empty()) throw Error("--cases", "no case named");

  // Inputs that must exist before anything runs.
  for (const CaseSpec* c : plan) {
    const SceneSpec& s = scene_spec(c->scene);
    if (!*s.preset && !fs::is_directory(fs::path(o_.datasets) / s.key))
      throw Error(o_.datasets, std::string("no data set '") + s.key + "' for case " + c->name +
                                   " (give the shared data sets' folder with --datasets, or leave the case out)");
  }
  if (!o_.glossy_data.empty()) {
    if (!fs::is_directory(o_.glossy_data)) throw Error(o_.glossy_data, "not a data set folder");
    if (!has_normal_maps(o_.glossy_data))
      for (const CaseSpec* c : plan)
        if (c->name == "no_normal_prior")  // the other cases run without the prior, with a note
          throw Error(o_.glossy_data, "case " + c->name + " compares with the normal prior and this data set has "
                                      "no normal-prior maps train/gt/normal_*.exr (a `goris synth` scene has them)");
  }
  if (fs::exists(out_) && !fs::is_directory(out_)) throw Error(out_.string(), "exists and is not a folder");
  fs::create_directories(out_ / "runs");

  std::vector<Row> rows;
  for (const CaseSpec* c : plan) {
    rows.push_back(run_case(*c));
    write_outputs(rows, plan);  // a long bench shows its results so far
  }
  int ok = 0, failed = 0, non_finite = 0, degraded = 0;
  for (const Row& r : rows) {
    ok += r.status == "ok", failed += r.status == "failed", non_finite += r.status == "non-finite";
    degraded += delta_of(r, rows).degraded();
  }
  std::printf("\nwrote %s and %s: %zu cases, %d ok (%d of them degrade against their reference), %d failed, %d with "
              "non-finite outputs\n",
              (out_ / "results.csv").c_str(), (out_ / "results.md").c_str(), rows.size(), ok, degraded, failed,
              non_finite);
  if (failed || non_finite) goris::cli::set_exit_code(1);
}

void setup_bench_stability(CLI::App& root) {
  auto& bench = goris::bench::bench_group(root);
  auto o = std::make_shared<Options>();
  std::string names;
  for (const auto& c : cases()) names += (names.empty() ? "" : ", ") + c.name;
  auto* c = bench.add_subcommand(
      "stability",
      "The method's failure cases end to end: finished?, finite outputs?, metrics, NaN skips, degradation");
  c->add_option("--out", o->out, "Output folder (results.csv, results.md, scenes/, runs/)")->required();
  c->add_option("--cases", o->cases, "Comma-separated cases (each runs with its reference) or all: " + names)
      ->capture_default_str();
  c->add_option("--schedule", o->schedule, "short (500 stage-1 iterations at 128 px) or medium (2000)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& s) {  // "tiny" is the CLI test's schedule, left out of the help
            return s == "short" || s == "medium" || s == "tiny" ? std::string() : "unknown schedule '" + s + "'";
          },
          "short|medium"));
  goris::cli::add_device_option(*c, o->device);
  c->add_option("--datasets", o->datasets, "Folder of the shared data sets (lambert_room, twin_mirrors)")
      ->capture_default_str();
  c->add_option("--glossy-data", o->glossy_data,
                "Use this data set as the glossy scene of the reference, weight, prior, mask and single-view cases "
                "instead of generating one with goris synth");
  c->callback([o] { Bench(*o).run(); });
}

}  // namespace
GORIS_COMMAND(86, setup_bench_stability);
