// Fault injection on `goris train`, `goris remove` and `goris export` (ctest -L faults): each command runs
// on a tiny copy of the embedded default scene and is stopped at random moments by SIGKILL, SIGTERM or
// SIGINT (checkpoints are written every iteration, so many stops land in a checkpoint write), then run
// again the way a user would (--resume, --restart, the same command) until it finishes. Checked after
// every stop and at the end:
//   - the exit status: 128 + the signal for an interrupted SIGTERM/SIGINT, 0 only for a finished command;
//   - no folder is unusable: the next command succeeds, every model file present reads (`goris info`);
//   - nothing stale: a removal whose options change between the stop and the rerun ends equal to an
//     uninterrupted removal with the new options;
//   - the result is bit-identical to an uninterrupted run (point_cloud.ply, exported files), and no
//     temporary file is left behind.
// Usage: fault_driver GORIS DATA WORK [--kills N] [--seed S] [--only train,intrinsic,remove,export]
// Prints the seed and a summary; exits 1 on any failure.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "process.h"

namespace fs = std::filesystem;
using goris::faults::describe;
using goris::faults::Outcome;
using goris::faults::read_all;
using goris::faults::run_process;

namespace {

struct Totals {
  int kills = 0, by_signal[32] = {}, mid_write = 0, cycles = 0, finished = 0, stale_chances = 0;
  std::vector<std::string> failures;
};

struct Driver {
  std::string goris;
  fs::path data, work;
  std::mt19937_64 rng;
  Totals t;

  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  bool chance(double p) { return uniform(0, 1) < p; }

  void fail(const std::string& what) {
    std::printf("FAIL: %s\n", what.c_str());
    std::fflush(stdout);
    t.failures.push_back(what);
  }

  Outcome goris_run(std::vector<std::string> args, const fs::path& log, double delay = -1, int sig = 0,
                    const std::function<bool()>& now = {}) {
    args.insert(args.begin(), goris);
    return run_process(args, log, delay, sig, now);
  }

  // A signal and a moment: a fifth of the stops within the first 5 % (start-up, loading), the others
  // anywhere in the command's usual duration and a little past it.
  std::pair<int, double> pick_stop(double usual_s) {
    const double r = uniform(0, 1);
    const int sig = r < 0.4 ? SIGKILL : r < 0.7 ? SIGTERM : SIGINT;
    const double at = chance(0.2) ? uniform(0, 0.05 * usual_s) : uniform(0, 1.1 * usual_s);
    return {sig, at};
  }

  // The status a stopped command may end with: finished (0), interrupted cleanly (128 + signal, saying
  // so), or killed by the signal itself (SIGKILL always; SIGTERM/SIGINT before the handlers are in place).
  void check_status(const std::string& where, const Outcome& o, int sig, const fs::path& finished_file) {
    if (o.exited && o.code == 0) {
      if (!fs::exists(finished_file)) fail(where + ": exit status 0 but " + finished_file.string() + " is missing");
      return;
    }
    if (o.exited && sig != SIGKILL && o.code == 128 + sig) {
      if (o.out.find("interrupted") == std::string::npos) fail(where + ": exit status " + std::to_string(o.code) + " without 'interrupted'");
      return;
    }
    if (!o.exited && o.code == sig) return;
    fail(where + ": after signal " + std::to_string(sig) + ", " + describe(o) + "\n" + o.err);
  }

  void count_kill(int sig, const fs::path& dir) {
    ++t.kills;
    ++t.by_signal[sig];
    if (sig == SIGKILL && has_temp_files(dir)) ++t.mid_write;
  }

  static bool is_temp_name(const std::string& name) { return name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos; }

  static bool has_temp_files(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return false;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
      if (is_temp_name(e.path().filename().string())) return true;
    return false;
  }

  // Every model file present must read.
  void check_models_read(const std::string& where, const std::vector<fs::path>& files, const fs::path& log) {
    for (const fs::path& f : files) {
      if (!fs::exists(f)) continue;
      const Outcome o = goris_run({"info", f.string()}, log);
      if (!(o.exited && o.code == 0)) fail(where + ": goris info " + f.string() + " failed (" + describe(o) + ")\n" + o.err);
    }
  }

  void check_same_bytes(const std::string& where, const fs::path& got, const fs::path& want) {
    if (!fs::exists(got)) return fail(where + ": " + got.string() + " is missing");
    if (read_all(got) != read_all(want)) fail(where + ": " + got.string() + " differs from the uninterrupted " + want.string());
  }

  void check_no_temp_files(const std::string& where, const fs::path& dir) {
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
      if (is_temp_name(e.path().filename().string())) fail(where + ": temporary file left: " + e.path().string());
  }

  // Runs `next()` (the command for the folder's current state) again and again, stopping it while
  // stops > 0 (each time with probability 0.85), until it finishes. Returns false when it never did;
  // `stops` is left with the stops that did not happen (the command ended first).
  bool until_finished(const std::string& name, double usual_s, int& stops, const fs::path& dir,
                      const fs::path& finished_file, const std::function<std::vector<std::string>()>& next,
                      const std::function<void(const Outcome&, int)>& after_stop) {
    for (int cycle = 0; cycle < 20; ++cycle) {
      ++t.cycles;
      const std::string where = name + " cycle " + std::to_string(cycle);
      const std::vector<std::string> args = next();
      const bool stop = stops > 0 && chance(0.85);
      auto [sig, at] = stop ? pick_stop(usual_s) : std::pair<int, double>{0, -1.0};
      // A quarter of the stops wait for a temporary file in `dir` (a checkpoint or an output being
      // written) and come at once, during that write.
      std::function<bool()> now;
      if (stop && chance(0.25)) {
        at = 2 * usual_s;
        now = [&dir] { return has_temp_files(dir); };
      }
      const Outcome o = goris_run(args, work / "last", at, sig, now);
      if (o.signalled_by_us) {
        --stops;
        count_kill(sig, dir);
        check_status(where, o, sig, finished_file);
        after_stop(o, sig);
        if (o.exited && o.code == 0) return true;
        continue;
      }
      if (!(o.exited && o.code == 0)) {
        std::string cmd;
        for (const auto& a : args) cmd += " " + a;
        fail(where + ": the folder is unusable: goris" + cmd + " gave " + describe(o) + "\n" + o.err);
        return false;
      }
      return true;
    }
    fail(name + ": never finished");
    return false;
  }
};

struct Scene {
  std::vector<std::string> train_args(const fs::path& data, const fs::path& run, const std::string& mode) const {
    return {"train", data.string(), "--out", run.string(), "--mode", mode, "--device", "cpu", "--resolution",
            "24", "--init-points", "600", "--iters", mode == "intrinsic" ? "12" : "24", "--checkpoint-every", "1",
            "--seed", "5"};
  }
};

// goris train (mode radiance or intrinsic): stopped, then --resume (a checkpoint), --restart (config.json
// without a checkpoint) or the first command again (nothing), until it finishes bit-identical to `ref`.
void train_trials(Driver& d, const std::string& mode, int kills, double usual_s, const fs::path& ref) {
  const Scene s;
  const fs::path run = d.work / ("train_" + mode);
  int trial = 0;
  while (kills > 0 && trial < 500) {
    fs::remove_all(run);
    int stops = std::min(kills, 1 + int(d.rng() % 4));
    kills -= stops;
    const std::string name = "train " + mode + " trial " + std::to_string(trial++);
    auto next = [&]() -> std::vector<std::string> {
      bool has_ckpt = false;  // a checkpoint file, not only the temporary file of one being written
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(run / "checkpoints", ec))
        has_ckpt = has_ckpt || (e.path().extension() == ".ckpt" && !Driver::is_temp_name(e.path().filename().string()));
      if (has_ckpt) return {"train", d.data.string(), "--out", run.string(), "--resume"};
      std::vector<std::string> a = s.train_args(d.data, run, mode);
      if (fs::exists(run / "config.json")) a.push_back("--restart");
      return a;
    };
    auto after_stop = [&](const Outcome& o, int sig) {
      if (o.exited && o.code == 128 + sig && !fs::exists(run / "checkpoints"))
        d.fail(name + ": interrupted cleanly but no checkpoint was written");
      d.check_models_read(name, {run / "point_cloud.ply"}, d.work / "info");
    };
    const bool finished = d.until_finished(name, usual_s, stops, run, run / "point_cloud.ply", next, after_stop);
    kills += stops;  // those that did not happen
    if (!finished) continue;
    ++d.t.finished;
    d.check_same_bytes(name, run / "point_cloud.ply", ref / "point_cloud.ply");
    d.check_no_temp_files(name, run);
  }
}

// goris remove on a copy of a trained, selected run: stopped and run again, sometimes with other options
// (the stale case), until it finishes equal to an uninterrupted removal with the last options.
void remove_trials(Driver& d, int kills, double usual_s, const fs::path& base,
                   const std::vector<std::vector<std::string>>& options, const std::vector<fs::path>& refs) {
  const fs::path run = d.work / "remove";
  int trial = 0;
  while (kills > 0 && trial < 500) {
    fs::remove_all(run);
    fs::copy(base, run, fs::copy_options::recursive);
    int stops = std::min(kills, 1 + int(d.rng() % 4));
    kills -= stops;
    const std::string name = "remove trial " + std::to_string(trial++);
    std::size_t opt = d.rng() % options.size();
    auto next = [&]() {
      std::vector<std::string> a = {"remove", run.string(), "--device", "cpu"};
      a.insert(a.end(), options[opt].begin(), options[opt].end());
      return a;
    };
    auto after_stop = [&](const Outcome&, int) {
      d.check_models_read(name, {run / "removal" / "point_cloud.ply"}, d.work / "info");
      if (d.chance(0.35)) {  // the next run changes its options: nothing of the stopped one may be reused
        opt = (opt + 1) % options.size();
        ++d.t.stale_chances;
      }
    };
    const bool finished = d.until_finished(name, usual_s, stops, run, run / "removal" / "point_cloud.ply", next, after_stop);
    kills += stops;
    if (!finished) continue;
    ++d.t.finished;
    d.check_same_bytes(name + " (options " + std::to_string(opt) + ")", run / "removal" / "point_cloud.ply",
                       refs[opt] / "removal" / "point_cloud.ply");
    d.check_no_temp_files(name, run);
  }
}

std::vector<std::string> export_files() { return {"model.ply", "baked.ply", "baked.json", "model.spz", "model.splat", "model.glb"}; }

std::vector<std::string> export_args(const fs::path& run, const fs::path& out) {
  return {"export", run.string(), "--device", "cpu", "--ply", (out / "model.ply").string(), "--baked",
          (out / "baked.ply").string(), "--spz", (out / "model.spz").string(), "--splat", (out / "model.splat").string(),
          "--glb", (out / "model.glb").string(), "--renders", (out / "frames").string(), "--frames", "3"};
}

// goris export of a trained run: stopped and run again until it finishes; every output present after a
// stop is either complete (equal to the uninterrupted export's) or absent.
void export_trials(Driver& d, int kills, double usual_s, const fs::path& run, const fs::path& ref) {
  const fs::path out = d.work / "export";
  int trial = 0;
  while (kills > 0 && trial < 500) {
    fs::remove_all(out);
    fs::create_directories(out);
    int stops = std::min(kills, 1 + int(d.rng() % 4));
    kills -= stops;
    const std::string name = "export trial " + std::to_string(trial++);
    auto next = [&] { return export_args(run, out); };
    auto after_stop = [&](const Outcome& o, int sig) {
      if (o.exited && o.code == 128 + sig) return;  // a clean stop may write the baked model so far
      for (const std::string& f : export_files())
        if (fs::exists(out / f) && f != "baked.json") d.check_same_bytes(name + " after a stop", out / f, ref / f);
      d.check_models_read(name, {out / "model.ply", out / "baked.ply"}, d.work / "info");
    };
    const bool finished = d.until_finished(name, usual_s, stops, out, out / "frames" / "contact_sheet.png", next, after_stop);
    kills += stops;
    if (!finished) continue;
    ++d.t.finished;
    for (const std::string& f : export_files())
      if (f != "baked.json") d.check_same_bytes(name, out / f, ref / f);
    for (const auto& e : fs::directory_iterator(ref / "frames"))
      d.check_same_bytes(name, out / "frames" / e.path().filename(), e.path());
    d.check_no_temp_files(name, out);
  }
}

// Runs a command that must succeed, for the references; returns its duration.
double must(Driver& d, const std::vector<std::string>& args) {
  const Outcome o = d.goris_run(args, d.work / "reference");
  if (!(o.exited && o.code == 0)) {
    std::fprintf(stderr, "fault_driver: reference command %s failed (%s)\n%s\n", args[0].c_str(), describe(o).c_str(), o.err.c_str());
    std::exit(2);
  }
  return o.seconds;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: fault_driver GORIS DATA WORK [--kills N] [--seed S] [--only train,intrinsic,remove,export]\n");
    return 2;
  }
  Driver d;
  d.goris = argv[1];
  d.data = fs::absolute(argv[2]);
  d.work = fs::absolute(argv[3]);
  int kills = 200;
  std::uint64_t seed = std::random_device{}();
  std::set<std::string> only = {"train", "intrinsic", "remove", "export"};
  for (int i = 4; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--kills") kills = std::atoi(v.c_str());
    else if (k == "--seed") seed = std::strtoull(v.c_str(), nullptr, 10);
    else if (k == "--only") {
      only.clear();
      for (std::size_t a = 0, b; a <= v.size(); a = b + 1) {
        b = v.find(',', a);
        if (b == std::string::npos) b = v.size();
        only.insert(v.substr(a, b - a));
      }
    } else {
      std::fprintf(stderr, "fault_driver: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  std::printf("fault_driver: seed %llu, %d stops (rerun with --seed %llu)\n", (unsigned long long)seed, kills,
              (unsigned long long)seed);
  std::fflush(stdout);
  d.rng.seed(seed);
  fs::remove_all(d.work);
  fs::create_directories(d.work);
  const Scene s;

  // Uninterrupted references.
  const fs::path ref_r = d.work / "ref_radiance", ref_i = d.work / "ref_intrinsic", sel = d.work / "ref_selected";
  const double t_train = must(d, s.train_args(d.data, ref_r, "radiance"));
  double t_intrinsic = 0;
  if (only.count("intrinsic")) t_intrinsic = must(d, s.train_args(d.data, ref_i, "intrinsic"));
  const std::vector<std::vector<std::string>> remove_options = {{"--iters", "6"}, {"--iters", "6", "--ablate", "shadows"}};
  std::vector<fs::path> remove_refs;
  double t_remove = 0;
  if (only.count("remove")) {
    fs::copy(ref_r, sel, fs::copy_options::recursive);
    must(d, {"select", sel.string(), "--masks", "--device", "cpu"});
    for (std::size_t k = 0; k < remove_options.size(); ++k) {
      const fs::path r = d.work / ("ref_removed_" + std::to_string(k));
      fs::copy(sel, r, fs::copy_options::recursive);
      std::vector<std::string> a = {"remove", r.string(), "--device", "cpu"};
      a.insert(a.end(), remove_options[k].begin(), remove_options[k].end());
      t_remove = std::max(t_remove, must(d, a));
      remove_refs.push_back(r);
    }
  }
  const fs::path ref_x = d.work / "ref_export";
  double t_export = 0;
  if (only.count("export")) {
    fs::create_directories(ref_x);
    t_export = must(d, export_args(ref_r, ref_x));
  }
  std::printf("uninterrupted: train %.2f s, intrinsic %.2f s, remove %.2f s, export %.2f s\n", t_train, t_intrinsic,
              t_remove, t_export);
  std::fflush(stdout);

  // The stops, shared out over the commands.
  std::vector<std::string> order;
  for (const char* n : {"train", "intrinsic", "remove", "export"})
    if (only.count(n)) order.push_back(n);
  std::map<std::string, int> share;
  for (std::size_t i = 0; i < order.size(); ++i) share[order[i]] = kills / int(order.size()) + (int(i) < kills % int(order.size()));
  for (const auto& n : order) {
    const int before = d.t.kills;
    const std::size_t failed = d.t.failures.size();
    if (n == "train") train_trials(d, "radiance", share[n], t_train, ref_r);
    if (n == "intrinsic") train_trials(d, "intrinsic", share[n], t_intrinsic, ref_i);
    if (n == "remove") remove_trials(d, share[n], t_remove, sel, remove_options, remove_refs);
    if (n == "export") export_trials(d, share[n], t_export, ref_r, ref_x);
    std::printf("%-9s %3d stops, %zu failures\n", n.c_str(), d.t.kills - before, d.t.failures.size() - failed);
    std::fflush(stdout);
  }

  std::printf("fault_driver: seed %llu: %d stops (SIGKILL %d, of which %d mid-write; SIGTERM %d; SIGINT %d) in %d "
              "commands; %d runs finished; %d option changes after a stop; %zu failures\n",
              (unsigned long long)seed, d.t.kills, d.t.by_signal[SIGKILL], d.t.mid_write, d.t.by_signal[SIGTERM],
              d.t.by_signal[SIGINT], d.t.cycles, d.t.finished, d.t.stale_chances, d.t.failures.size());
  return d.t.failures.empty() ? 0 : 1;
}
