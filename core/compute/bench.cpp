#include "core/compute/bench.h"

#include "core/compute/memory.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

namespace goris {

Timing time_repeated(const std::function<void()>& fn, int repeats, int warmup, const std::function<void()>& sync) {
  for (int i = 0; i < warmup; ++i) fn();
  if (sync) sync();
  std::vector<double> ms;
  ms.reserve(std::max(repeats, 1));
  for (int i = 0; i < std::max(repeats, 1); ++i) {
    auto t0 = std::chrono::steady_clock::now();
    fn();
    if (sync) sync();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  Timing t;
  t.repeats = int(ms.size());
  t.min_ms = ms.front();
  t.max_ms = ms.back();
  t.median_ms = ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
  return t;
}

std::string cpu_description() {
  std::ifstream f("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return model + " (" + std::to_string(std::thread::hardware_concurrency()) + " threads)";
}

double peak_host_memory_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::string peak_memory_text() {
  char buf[96];
  const double gpu = double(device_memory_stats(Device::CUDA).peak_in_use) / 1048576.0;
  if (gpu > 0)
    std::snprintf(buf, sizeof buf, "%.0f MiB host, %.0f MiB GPU", peak_host_memory_mib(), gpu);
  else
    std::snprintf(buf, sizeof buf, "%.0f MiB", peak_host_memory_mib());
  return buf;
}

}  // namespace goris
