#pragma once
// Learning-rate schedules.
#include <algorithm>
#include <cmath>

namespace goris {

// Log-linear decay from lr_init at step 0 to lr_final at max_steps, constant after (3DGS's
// get_expon_lr_func without the delay). max_steps <= 0: always lr_init.
inline float exponential_lr(int step, float lr_init, float lr_final, int max_steps) {
  if (max_steps <= 0 || lr_init <= 0 || lr_final <= 0) return lr_init;
  const double t = std::clamp(double(step) / double(max_steps), 0.0, 1.0);
  return float(std::exp(std::log(double(lr_init)) * (1.0 - t) + std::log(double(lr_final)) * t));
}

}  // namespace goris
