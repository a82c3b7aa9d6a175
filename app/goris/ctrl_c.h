#pragma once
// Ctrl-C for long commands (train, remove, export): while a CtrlC object lives, the first SIGINT raises
// stop_flag() (the work finishes its step, writes a checkpoint and returns) and a second one ends the
// process at once. The previous handler comes back when the object goes out of scope, also on exceptions.
#include <atomic>
#include <csignal>

namespace goris::cli {

inline std::atomic<bool>& stop_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

extern "C" inline void goris_on_sigint(int) {
  stop_flag() = true;
  std::signal(SIGINT, SIG_DFL);
}

class CtrlC {
 public:
  CtrlC() : previous_(std::signal(SIGINT, goris_on_sigint)) { stop_flag() = false; }
  ~CtrlC() { std::signal(SIGINT, previous_); }
  CtrlC(const CtrlC&) = delete;
  CtrlC& operator=(const CtrlC&) = delete;
  const std::atomic<bool>* flag() const { return &stop_flag(); }

 private:
  void (*previous_)(int);
};

}  // namespace goris::cli
