#pragma once
// Small helpers for benchmark programs (never for timed tests): repeated timing with medians, the
// machine's description and peak memory, so every reported number carries its conditions.
#include <functional>
#include <string>
#include <vector>

namespace goris {

struct Timing {
  double median_ms = 0, min_ms = 0, max_ms = 0;
  int repeats = 0;
};

// Runs fn `warmup` times untimed, then `repeats` times timed; `sync` (if given) runs before each clock read
// so asynchronous GPU work is counted.
Timing time_repeated(const std::function<void()>& fn, int repeats, int warmup = 1,
                     const std::function<void()>& sync = {});

// "Intel Xeon ... (2 cores)" from /proc/cpuinfo and the hardware concurrency.
std::string cpu_description();
// Peak resident set size of this process in MiB.
double peak_host_memory_mib();
// "512 MiB" (host), or "512 MiB host, 300 MiB GPU" once CUDA memory was used (its peak in use).
std::string peak_memory_text();

}  // namespace goris
