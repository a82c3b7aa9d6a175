#pragma once
// Runs one shell command line as a child process with a time limit: /bin/sh -c COMMAND, stdin from
// /dev/null, stdout and stderr together into a log file. The child leads its own process group, so a
// time-out (or a stop request) kills the shell and everything it started. posix_spawn (not a bare fork)
// keeps this safe in a program whose other threads (TBB) are running.
#include <filesystem>
#include <functional>
#include <string>

namespace goris {

struct ShellResult {
  bool timed_out = false;  // killed at the time limit
  bool stopped = false;    // killed because should_stop() returned true
  int exit_code = -1;      // when the shell exited normally
  int signal = 0;          // when it died from a signal (not counting our own kill)
  double seconds = 0;
  bool ok() const { return !timed_out && !stopped && signal == 0 && exit_code == 0; }
};

// Throws goris::Error only when the process cannot be started (or the log file cannot be created).
// should_stop (optional) is polled about every 50 ms.
ShellResult run_shell_command(const std::string& command, double timeout_s, const std::filesystem::path& log_path,
                              const std::function<bool()>& should_stop = {});

// The last `max_lines` lines (at most `max_bytes` bytes) of a text file; "" when it is missing or empty.
std::string file_tail(const std::filesystem::path& path, int max_lines = 15, std::size_t max_bytes = 4096);

// `s` as one single-quoted /bin/sh word.
std::string shell_quote(const std::string& s);

}  // namespace goris
