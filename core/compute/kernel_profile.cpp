#include "core/compute/kernel_profile.h"

#include "core/compute/memory.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <utility>

namespace goris::kernel_profile {
namespace {

std::mutex g_mutex;
std::map<std::pair<std::string, unsigned>, SiteTime> g_sites;  // keyed by file and line

// "void goris::shading::ops::backend_host::shade(...) [with T = float]" -> "goris::shading::ops::shade<float>"
std::string short_function(const char* pretty) {
  std::string s(pretty);
  std::string templ;  // "[with goris::Device D = goris::Device::CPU; T = float]" -> "<CPU, float>"
  if (const auto w = s.find(" [with "); w != std::string::npos) {
    const std::string with = s.substr(w + 7, s.rfind(']') - w - 7);
    for (std::size_t at = 0; at < with.size();) {
      const auto eq = with.find(" = ", at), end = std::min(with.find("; ", at), with.size());
      if (eq == std::string::npos || eq > end) break;
      std::string value = with.substr(eq + 3, end - eq - 3);
      if (value.rfind("goris::Device::", 0) == 0) value.erase(0, 15);
      if (value.find("<lambda") != std::string::npos) value = "lambda";  // a callback's type: long, says little
      templ += (templ.empty() ? "<" : ", ") + value;
      at = end + 2;
    }
    if (!templ.empty()) templ += ">";
    s.resize(w);
  }
  if (const auto p = s.find('('); p != std::string::npos) s.resize(p);
  if (const auto sp = s.rfind(' '); sp != std::string::npos) s = s.substr(sp + 1);
  for (const char* ns : {"backend_host::", "backend_nvcc::"})
    for (auto at = s.find(ns); at != std::string::npos; at = s.find(ns)) s.erase(at, std::char_traits<char>::length(ns));
  return s + templ;
}

std::string file_name(const char* path) {
  const std::string p(path);
  const auto slash = p.find_last_of('/');
  return slash == std::string::npos ? p : p.substr(slash + 1);
}

}  // namespace

void enable(bool on) { g_enabled.store(on, std::memory_order_relaxed); }

void reset() {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_sites.clear();
}

void record(const std::source_location& site, double ms) {
  std::lock_guard<std::mutex> lock(g_mutex);
  SiteTime& t = g_sites[{site.file_name(), site.line()}];
  if (t.calls == 0) {
    t.function = short_function(site.function_name());
    t.where = file_name(site.file_name()) + ":" + std::to_string(site.line());
  }
  ++t.calls;
  t.ms += ms;
}

Scope::Scope(Device device, const std::source_location& site) : device_(device), site_(site), on_(enabled()) {
  if (!on_) return;
  device_synchronize(device_);  // earlier asynchronous work is not this block's
  t0_ = std::chrono::steady_clock::now();
}

Scope::~Scope() {
  if (!on_) return;
  device_synchronize(device_);
  record(site_, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count());
}

std::vector<SiteTime> sites() {
  std::vector<SiteTime> v;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    for (const auto& [key, t] : g_sites) v.push_back(t);
  }
  std::sort(v.begin(), v.end(), [](const SiteTime& a, const SiteTime& b) { return a.ms > b.ms; });
  return v;
}

std::string markdown_table() {
  const std::vector<SiteTime> v = sites();
  double total = 0;
  long calls = 0;
  for (const SiteTime& t : v) total += t.ms, calls += t.calls;
  char line[512];
  std::snprintf(line, sizeof line, "%ld launches (parallel_for and timed blocks) at %zu sites, %.3f ms in all\n\n", calls,
                v.size(), total);
  std::string s = line;
  s += "| launch site | where | calls | total ms | mean us | share |\n|---|---|--:|--:|--:|--:|\n";
  for (const SiteTime& t : v) {
    std::snprintf(line, sizeof line, "| %s | %s | %ld | %.3f | %.1f | %.1f %% |\n", t.function.c_str(), t.where.c_str(),
                  t.calls, t.ms, 1000.0 * t.ms / double(t.calls), total > 0 ? 100.0 * t.ms / total : 0.0);
    s += line;
  }
  return s;
}

}  // namespace goris::kernel_profile
