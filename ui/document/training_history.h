#pragma once
// The curves of the Training panel (loss, PSNR, Gaussian count, iterations/s against the iteration).
// Bounded: when full, every other sample is dropped and only every 2nd, 4th... later sample is kept, so a
// 30K-iteration run costs the same memory as a short one and the plot still spans the whole run.
#include <cstddef>
#include <vector>

namespace goris::ui {

struct ProgressSample {
  int iteration = 0;
  float loss = 0, psnr = 0, gaussians = 0, it_per_s = 0;
};

class TrainingHistory {
 public:
  explicit TrainingHistory(size_t capacity = 2048) : capacity_(capacity < 4 ? 4 : capacity) {}
  void add(const ProgressSample& s);
  void clear();
  const std::vector<ProgressSample>& samples() const { return samples_; }
  // One field of every sample, as ImGui::PlotLines reads it.
  std::vector<float> series(float ProgressSample::*field) const;
  size_t capacity() const { return capacity_; }

 private:
  size_t capacity_;
  std::vector<ProgressSample> samples_;
  int stride_ = 1;   // keep one sample in `stride_` offered
  int skipped_ = 0;  // offered since the last kept one
};

}  // namespace goris::ui
