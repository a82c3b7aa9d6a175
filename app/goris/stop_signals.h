#pragma once
// Ctrl-C for long commands (train, remove, export): while a CtrlC object lives, the first SIGINT raises
// stop_flag() (the work finishes its step, writes a checkpoint and returns) and a second one ends the
// process at once. The previous handler comes back when the object goes out of scope, also on exceptions.
//
// A second SIGINT within half a second of the first counts as the same Ctrl-C: tools such as timeout(1)
// deliver one interrupt twice (to the child, then to its process group), and a person who means "now"
// presses again later than that.
#include <atomic>
#include <csignal>
#include <ctime>

namespace goris::cli {

inline std::atomic<bool>& stop_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

inline std::atomic<long long>& first_sigint_ms() {
  static std::atomic<long long> ms{0};
  return ms;
}

extern "C" inline void goris_on_sigint(int) {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe
  const long long ms = static_cast<long long>(now.tv_sec) * 1000 + now.tv_nsec / 1000000;
  if (!stop_flag().exchange(true)) {
    first_sigint_ms() = ms;
    return;
  }
  if (ms - first_sigint_ms() < 500) return;
  std::signal(SIGINT, SIG_DFL);
  std::raise(SIGINT);
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
