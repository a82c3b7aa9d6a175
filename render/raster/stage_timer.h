#pragma once
// Wall-clock stage timer for RasterSettings::profile: synchronises the device before each reading so that
// asynchronous CUDA work is charged to the stage that queued it. Does nothing when profiling is off.
#include <chrono>

#include "core/compute/memory.h"

namespace goris::raster {

class StageTimer {
 public:
  StageTimer(bool on, Device d) : on_(on), dev_(d) { reset(); }
  // Milliseconds since the last lap (0 when off), and restarts.
  double lap() {
    if (!on_) return 0;
    device_synchronize(dev_);
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - t0_).count();
    t0_ = now;
    return ms;
  }
  void reset() {
    if (on_) t0_ = std::chrono::steady_clock::now();
  }

 private:
  bool on_;
  Device dev_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace goris::raster
