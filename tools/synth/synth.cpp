#include "tools/synth/synth.h"

#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "tools/synth/blender_process.h"
#include "tools/synth/contact_sheet.h"

namespace goris::synth {
namespace fs = std::filesystem;

namespace {
void write_text(const fs::path& path, const std::string& text) {
  fs::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream f(tmp);
    f << text;
    if (!f.flush()) throw Error(tmp.string(), "cannot write");
  }
  fs::rename(tmp, path);
}

// OUT may be absent, empty, or an earlier synth output (it has scene.json); anything else is kept.
void check_out_dir(const fs::path& out) {
  if (!fs::exists(out)) return;
  if (!fs::is_directory(out)) throw Error(out.string(), "exists and is not a folder");
  if (!fs::is_empty(out) && !fs::exists(out / "scene.json"))
    throw Error(out.string(), "is not empty and not a `goris synth` output (no scene.json): choose another --out");
}

bool parse_frame(const std::string& line, int& done, int& total) {
  return std::sscanf(line.c_str(), "GORIS_FRAME %d %d", &done, &total) == 2;
}

// Runs the scene script on `scene_json` into `dir` (with `mode` as its third argument when not empty),
// logging to dir/blender.log. On failure the log moves to `failed_log`, `dir` goes, and the error quotes the
// log's last lines.
void run_scene_script(const fs::path& blender, const fs::path& script, const fs::path& scene_json, const fs::path& dir,
                      const std::string& mode, const std::function<void(int, int)>& on_frame, const fs::path& failed_log) {
  std::vector<std::string> argv = {"-b", "--factory-startup", "--python-exit-code", "1", "--python",
                                   fs::absolute(script).string(), "--", scene_json.string(), dir.string()};
  if (!mode.empty()) argv.push_back(mode);
  bool finished = false;
  ProcessResult r = run_logged(blender, argv, dir / "blender.log", [&](const std::string& line) {
    int done = 0, total = 0;
    if (parse_frame(line, done, total) && on_frame) on_frame(done, total);
    if (line.rfind("GORIS_DONE", 0) == 0) finished = true;
  });
  if (r.exit_code == 0 && finished) return;
  fs::create_directories(failed_log.parent_path());
  fs::rename(dir / "blender.log", failed_log);
  fs::remove_all(dir);
  std::string tail;
  for (const auto& l : r.last_lines) tail += "\n  " + l;
  throw Error(failed_log.string(), (r.exit_code != 0 ? "Blender exited with code " + std::to_string(r.exit_code)
                                                     : std::string("Blender stopped before rendering every view")) +
                                       "; last lines of the log:" + tail);
}
}  // namespace

void run_synth(const SynthJob& job) {
  SceneDescription scene = make_scene(job.options);
  if (!fs::is_regular_file(job.script)) throw Error(job.script.string(), "the Blender scene script is missing");
  fs::path blender = find_blender(job.blender);
  fs::path out = job.out.has_filename() ? job.out : job.out.parent_path();
  check_out_dir(out);

  fs::path staging = out;
  staging += ".synth-tmp";
  fs::remove_all(staging);
  fs::create_directories(staging);
  write_text(staging / "scene.json", to_json(scene).dump(1) + "\n");

  run_scene_script(blender, job.script, staging / "scene.json", staging, "", job.on_frame, out / "blender.log");
  if (job.contact_sheet) write_contact_sheet(staging, staging / "contact_sheet.png");
  fs::remove_all(out);
  fs::rename(staging, out);
}

void render_train_after(const TrainAfterJob& job) {
  const fs::path scene_json = job.data / "scene.json";
  if (!fs::is_regular_file(scene_json))
    throw Error(job.data.string(), "is not a `goris synth` data set (no scene.json)");
  if (!fs::is_regular_file(job.script)) throw Error(job.script.string(), "the Blender scene script is missing");
  const fs::path blender = find_blender(job.blender);
  const fs::path staging = job.data / "train_after.synth-tmp";
  fs::remove_all(staging);
  fs::create_directories(staging);
  run_scene_script(blender, job.script, scene_json, staging, "train-after", job.on_frame,
                   job.data / "blender_train_after.log");
  fs::remove_all(job.data / "train_after");
  fs::rename(staging / "train_after", job.data / "train_after");
  fs::remove_all(staging);
}

}  // namespace goris::synth
