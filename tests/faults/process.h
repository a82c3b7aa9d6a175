#pragma once
// Running goris as a child process for the fault-injection driver: optionally sending it a signal after a
// delay, and telling how it ended.
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace goris::faults {

struct Outcome {
  bool signalled_by_us = false;  // the signal was sent while the process still ran
  bool exited = false;           // exit() rather than death by a signal
  int code = 0;                  // exit status, or the signal that ended it
  double seconds = 0;
  std::string out, err;          // its stdout and stderr
};

inline std::string read_all(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs `args` (args[0] the program), stdout and stderr into files beside `log_stem`. When delay_s >= 0,
// sends `sig` after delay_s seconds, or as soon as `now()` (when given) turns true, unless the process has
// ended by then.
inline Outcome run_process(const std::vector<std::string>& args, const std::filesystem::path& log_stem,
                           double delay_s = -1, int sig = 0, const std::function<bool()>& now = {}) {
  const std::string out_path = log_stem.string() + ".out", err_path = log_stem.string() + ".err";
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    std::perror("fork");
    std::exit(2);
  }
  if (pid == 0) {
    if (!std::freopen(out_path.c_str(), "w", stdout) || !std::freopen(err_path.c_str(), "w", stderr)) _exit(126);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  Outcome o;
  int status = 0;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  bool done = false;
  if (delay_s >= 0) {
    while (!done && elapsed() < delay_s && !(now && now())) {
      done = waitpid(pid, &status, WNOHANG) == pid;
      if (!done) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (!done) {
      kill(pid, sig);
      o.signalled_by_us = true;
    }
  }
  if (!done) waitpid(pid, &status, 0);
  o.seconds = elapsed();
  o.exited = WIFEXITED(status);
  o.code = o.exited ? WEXITSTATUS(status) : WTERMSIG(status);
  o.out = read_all(out_path);
  o.err = read_all(err_path);
  return o;
}

inline std::string describe(const Outcome& o) {
  return o.exited ? "exit status " + std::to_string(o.code) : "killed by signal " + std::to_string(o.code);
}

}  // namespace goris::faults
