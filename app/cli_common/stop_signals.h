#pragma once
// Stopping long commands (train, remove, export, bench) cleanly: while a StopSignals object lives, the
// first SIGINT (Ctrl-C), SIGTERM (kill, timeout, docker stop, a cancelled CI job) or SIGHUP (a closed
// terminal) raises stop_flag() - the work finishes its step, writes a checkpoint and returns - and
// remembers the signal, so that the command can exit with the shell's status for it (128 + the signal:
// 130, 143, 129) and a script sees that the run did not finish. A second signal later ends the process at
// once. The previous handlers come back when the object goes out of scope, also on exceptions.
//
// A repeat of the first signal within half a second counts as the same request: tools such as timeout(1)
// deliver one interrupt twice (to the child, then to its process group), and a person who means "now"
// presses again later than that.
#include <atomic>
#include <csignal>
#include <ctime>
#include <string>

namespace goris::cli {

inline std::atomic<bool>& stop_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

// The signal that raised stop_flag(), 0 while none did.
inline std::atomic<int>& stop_signal() {
  static std::atomic<int> sig{0};
  return sig;
}

inline std::atomic<long long>& first_stop_ms() {
  static std::atomic<long long> ms{0};
  return ms;
}

extern "C" inline void goris_on_stop_signal(int sig) {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe
  const long long ms = static_cast<long long>(now.tv_sec) * 1000 + now.tv_nsec / 1000000;
  int none = 0;
  if (stop_signal().compare_exchange_strong(none, sig)) {
    first_stop_ms() = ms;
    stop_flag() = true;
    return;
  }
  if (sig == stop_signal() && ms - first_stop_ms() < 500) return;
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// The signals a StopSignals object handles.
inline constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

// "SIGINT", "SIGTERM", "SIGHUP" or "signal N".
inline std::string stop_signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal " + std::to_string(sig);
  }
}

class StopSignals {
 public:
  StopSignals() {
    stop_flag() = false;
    stop_signal() = 0;
    for (int i = 0; i < kCount; ++i) previous_[i] = std::signal(kStopSignals[i], goris_on_stop_signal);
  }
  ~StopSignals() {
    for (int i = 0; i < kCount; ++i) std::signal(kStopSignals[i], previous_[i]);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  const std::atomic<bool>* flag() const { return &stop_flag(); }
  // The signal that stopped the work, 0 if none came.
  int signal() const { return stop_signal(); }
  // The exit status of a command stopped by that signal (128 + the signal, as a shell reports a process
  // killed by it), 0 if none came.
  int exit_code() const { return signal() ? 128 + signal() : 0; }

 private:
  static constexpr int kCount = int(sizeof(kStopSignals) / sizeof(kStopSignals[0]));
  void (*previous_[kCount])(int);
};

}  // namespace goris::cli
