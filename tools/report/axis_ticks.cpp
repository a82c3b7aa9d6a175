#include "tools/report/axis_ticks.h"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/util/error.h"

namespace goris {
namespace {

double nice_step(double span, int target_ticks) {
  const double raw = span / std::max(1, target_ticks);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

void check_range(double lo, double hi, const char* what) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
    throw Error(what, "invalid axis range [" + tick_label(lo) + ", " + tick_label(hi) + "]");
}

}  // namespace

AxisRange log_axis_range(double lo, double hi) {
  check_range(lo, hi, "log axis");
  if (lo <= 0) throw Error("log axis", "values must be positive, got " + tick_label(lo));
  AxisRange r{std::pow(10.0, std::floor(std::log10(lo) + 1e-9)), std::pow(10.0, std::ceil(std::log10(hi) - 1e-9))};
  if (r.hi <= r.lo) r.hi = r.lo * 10;
  return r;
}

std::vector<double> log_ticks(const AxisRange& r) {
  std::vector<double> ticks;
  const int d0 = int(std::floor(std::log10(r.lo) + 1e-9)), d1 = int(std::ceil(std::log10(r.hi) - 1e-9));
  const bool fine = d1 - d0 < 3;
  for (int d = d0; d <= d1; ++d)
    for (double m : {1.0, 2.0, 5.0}) {
      if (m != 1.0 && !fine) continue;
      const double v = m * std::pow(10.0, d);
      if (v >= r.lo * (1 - 1e-9) && v <= r.hi * (1 + 1e-9)) ticks.push_back(v);
    }
  return ticks;
}

AxisRange linear_axis_range(double lo, double hi, int target_ticks) {
  check_range(lo, hi, "linear axis");
  if (hi - lo < 1e-12) {
    lo -= 1;
    hi += 1;
  }
  const double margin = 0.05 * (hi - lo);
  lo -= margin;
  hi += margin;
  const double step = nice_step(hi - lo, target_ticks);
  return {std::floor(lo / step) * step, std::ceil(hi / step) * step, step};
}

std::vector<double> linear_ticks(const AxisRange& r, int target_ticks) {
  const double step = r.step > 0 ? r.step : nice_step(r.hi - r.lo, target_ticks);
  std::vector<double> ticks;
  for (double k = std::ceil(r.lo / step - 1e-9); k * step <= r.hi + step * 1e-9; k += 1) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  }
  return ticks;
}

std::string tick_label(double v) {
  char b[64];
  if (std::abs(v) < 1e9)
    for (int p = 0; p <= 6; ++p) {
      std::snprintf(b, sizeof b, "%.*f", p, v);
      if (std::abs(std::strtod(b, nullptr) - v) <= 1e-9 * std::max(1e-6, std::abs(v))) return b;
    }
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace goris
