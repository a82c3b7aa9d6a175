#include "ui/shell/frame_limiter.h"

#include <algorithm>
#include <thread>

namespace goris::ui {

namespace {
double smooth(double old, double sample) { return old == 0 ? sample : 0.9 * old + 0.1 * sample; }
double ms(FrameLimiter::clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }
}  // namespace

FrameLimiter::FrameLimiter(double max_fps) : max_fps_(std::max(max_fps, 1.0)), target_fps_(max_fps_) {
  start_ = previous_start_ = clock::now();
}

void FrameLimiter::set_target_fps(double fps) { target_fps_ = std::clamp(fps, 1.0, max_fps_); }

void FrameLimiter::begin_frame(clock::time_point now) {
  if (frames_ > 0) {
    last_frame_ms_ = ms(now - previous_start_);
    frame_ms_ = smooth(frame_ms_, last_frame_ms_);
  }
  previous_start_ = start_ = now;
  ++frames_;
}

FrameLimiter::clock::duration FrameLimiter::end_frame(clock::time_point now) {
  work_ms_ = smooth(work_ms_, ms(now - start_));
  const auto period = std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(1.0 / target_fps_));
  const auto next = start_ + period;
  return next > now ? next - now : clock::duration::zero();
}

void FrameLimiter::end_frame_and_sleep() {
  const auto d = end_frame();
  if (d > clock::duration::zero()) std::this_thread::sleep_for(d);
}

}  // namespace goris::ui
