#pragma once
// Where the kernel time goes, per launch site: when enabled, every parallel_for and every Scope records its
// time under the file, line and function that called it (CPU: the wall time of the loop; CUDA: the kernel's
// time between two events, or the Scope's wall time between two synchronisations, so the run gets slower
// but each kernel's time is its own). Off by default: a disabled profile costs one relaxed atomic load per
// launch. Used by `goris bench intrinsic --kernels`; it needs no profiler on the machine (ncu is not
// everywhere).
#include <atomic>
#include <chrono>
#include <source_location>
#include <string>
#include <vector>

#include "core/compute/device.h"

namespace goris::kernel_profile {

inline std::atomic<bool> g_enabled{false};
inline bool enabled() { return g_enabled.load(std::memory_order_relaxed); }
void enable(bool on);
void reset();
void record(const std::source_location& site, double ms);

// Times a block that does not go through parallel_for (a hand-written CUDA launch, CUB, a TBB loop, Embree)
// under the site that constructs it: with the profile enabled it synchronises `device` before and after.
class Scope {
 public:
  explicit Scope(Device device, const std::source_location& site = std::source_location::current());
  ~Scope();
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  Device device_;
  std::source_location site_;
  bool on_;
  std::chrono::steady_clock::time_point t0_;
};

struct SiteTime {
  std::string function;  // the calling function, e.g. goris::shading::ops::shade<float>
  std::string where;     // file name and line of the parallel_for call
  long calls = 0;
  double ms = 0;
};
std::vector<SiteTime> sites();  // largest total time first

// The table `goris bench intrinsic --kernels` prints: site, calls, total ms, mean us, share.
std::string markdown_table();

}  // namespace goris::kernel_profile
