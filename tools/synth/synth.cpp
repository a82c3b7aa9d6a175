#include "tools/synth/synth.h"

#include <cstdio>
#include <fstream>

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

  bool finished = false;
  ProcessResult r = run_logged(blender,
                               {"-b", "--factory-startup", "--python-exit-code", "1", "--python", fs::absolute(job.script).string(),
                                "--", (staging / "scene.json").string(), staging.string()},
                               staging / "blender.log", [&](const std::string& line) {
                                 int done = 0, total = 0;
                                 if (parse_frame(line, done, total) && job.on_frame) job.on_frame(done, total);
                                 if (line.rfind("GORIS_DONE", 0) == 0) finished = true;
                               });
  if (r.exit_code != 0 || !finished) {
    fs::create_directories(out);
    fs::path log = out / "blender.log";
    fs::rename(staging / "blender.log", log);
    fs::remove_all(staging);
    std::string tail;
    for (const auto& l : r.last_lines) tail += "\n  " + l;
    throw Error(log.string(), (r.exit_code != 0 ? "Blender exited with code " + std::to_string(r.exit_code)
                                                : std::string("Blender stopped before rendering every view")) +
                                  "; last lines of the log:" + tail);
  }
  if (job.contact_sheet) write_contact_sheet(staging, staging / "contact_sheet.png");
  fs::remove_all(out);
  fs::rename(staging, out);
}

}  // namespace goris::synth
