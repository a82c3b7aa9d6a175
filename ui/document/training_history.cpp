#include "ui/document/training_history.h"

namespace goris::ui {

void TrainingHistory::add(const ProgressSample& s) {
  // A resumed or restarted run may go back in iterations: drop what lies ahead of it.
  bool rewound = false;
  while (!samples_.empty() && samples_.back().iteration >= s.iteration) {
    samples_.pop_back();
    rewound = true;
  }
  if (!rewound && !samples_.empty() && ++skipped_ < stride_) return;
  skipped_ = 0;
  samples_.push_back(s);
  if (samples_.size() >= capacity_) {
    size_t w = 0;
    for (size_t r = 0; r < samples_.size(); r += 2) samples_[w++] = samples_[r];
    samples_.resize(w);
    stride_ *= 2;
  }
}

void TrainingHistory::clear() {
  samples_.clear();
  stride_ = 1;
  skipped_ = 0;
}

std::vector<float> TrainingHistory::series(float ProgressSample::*field) const {
  std::vector<float> v;
  v.reserve(samples_.size());
  for (const ProgressSample& s : samples_) v.push_back(s.*field);
  return v;
}

}  // namespace goris::ui
