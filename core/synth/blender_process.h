#pragma once
// Finding and running Blender headless: the child's stdout and stderr are merged, copied line by line into
// a log file and handed to a callback (render_scene.py prints "GORIS_FRAME i n" after each view).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace goris::synth {

// `requested` (from --blender) when given, else `blender` on PATH. Throws goris::Error naming the
// install command when there is none.
std::filesystem::path find_blender(const std::filesystem::path& requested = {});

struct ProcessResult {
  int exit_code = 0;                     // the child's exit status; 128 + N when killed by signal N
  std::vector<std::string> last_lines;  // the last lines of output (at most 20), for error messages
};

// Runs `program args...`, writing everything it prints to `log_path`, and calls on_line for each line.
ProcessResult run_logged(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& log_path, const std::function<void(const std::string&)>& on_line);

}  // namespace goris::synth
