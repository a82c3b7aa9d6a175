#pragma once
// Running a helper program (Blender, COLMAP) as a child process: its stdout and stderr are merged, copied
// line by line into a log file and handed to a callback, so that the caller can show progress from what the
// program prints. The child leads its own process group: a stop request kills it and what it started.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace goris {

// `name` on PATH (the first executable file of that name), or nothing.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

struct ProcessResult {
  int exit_code = 0;                     // the child's exit status; 128 + N when killed by signal N
  bool stopped = false;                  // killed because should_stop() returned true
  std::vector<std::string> last_lines;  // the last lines of output (at most 20), for error messages
};

// Runs `program args...`, writing everything it prints to `log_path`, and calls on_line for each line (a
// carriage return also ends a line). should_stop (optional) is polled about every 100 ms. Throws
// goris::Error when the log file cannot be created or the program cannot be started.
ProcessResult run_logged(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& log_path, const std::function<void(const std::string&)>& on_line,
                         const std::function<bool()>& should_stop = {});

}  // namespace goris
