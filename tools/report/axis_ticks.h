#pragma once
// Axis ranges and tick positions for charts: a logarithmic axis (time) and a linear one (PSNR), both with
// "nice" values (1, 2, 5 times a power of ten) so the labels read well.
#include <string>
#include <vector>

namespace goris {

struct AxisRange {
  double lo = 0, hi = 1;
  double step = 0;  // linear axes: the tick step the range was rounded to (0: choose one)
};

// A log axis covering [lo, hi] (both > 0): widened to whole decades, at least one decade wide.
// Throws goris::Error when lo or hi is not a positive finite number or lo > hi.
AxisRange log_axis_range(double lo, double hi);
// Ticks inside `r`: the powers of ten, plus 2x and 5x of them when the range spans fewer than three decades.
std::vector<double> log_ticks(const AxisRange& r);

// A linear axis covering [lo, hi] with a margin, rounded outwards to the tick step; a zero-width range is
// widened by 1 each side. Throws goris::Error for non-finite input or lo > hi.
AxisRange linear_axis_range(double lo, double hi, int target_ticks = 5);
// Multiples of a 1/2/5 x 10^k step inside `r`, about `target_ticks` of them.
std::vector<double> linear_ticks(const AxisRange& r, int target_ticks = 5);

// A tick label: the shortest fixed-point text that shows the value ("0.5", "20", "1000"); %g beyond that.
std::string tick_label(double v);

}  // namespace goris
