#pragma once
// Caps the GUI's frame rate (the editor shares the CPU with the trainer) and measures frame times for the
// debug overlay.
#include <chrono>

namespace goris::ui {

class FrameLimiter {
 public:
  using clock = std::chrono::steady_clock;
  explicit FrameLimiter(double max_fps = 60.0);

  // The cap of the next frames, at most max_fps (the editor lowers it while only background work runs).
  void set_target_fps(double fps);
  double target_fps() const { return target_fps_; }
  // Marks the end of a frame's work; returns how long to sleep so frames start at most target_fps apart.
  clock::duration end_frame(clock::time_point now = clock::now());
  // end_frame() and sleeping that long.
  void end_frame_and_sleep();
  // Mark the start of the next frame (after any waiting for events, so idle time is not "work").
  void begin_frame(clock::time_point now = clock::now());

  double work_ms() const { return work_ms_; }              // last frame's work, smoothed
  double frame_ms() const { return frame_ms_; }            // start-to-start interval, smoothed
  double last_frame_ms() const { return last_frame_ms_; }  // the last start-to-start interval
  double max_fps() const { return max_fps_; }
  long frames() const { return frames_; }

 private:
  double max_fps_, target_fps_;
  clock::time_point start_{}, previous_start_{};
  double work_ms_ = 0, frame_ms_ = 0, last_frame_ms_ = 0;
  long frames_ = 0;
};

}  // namespace goris::ui
