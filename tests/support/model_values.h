#pragma once
// Every value of a model and its Adam moments, flattened on the host: two trainings that should agree bit
// for bit compare these with EXPECT_EQ.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/scene/gaussians.h"

namespace goris::test {

inline std::vector<float> all_values(const GaussianModel& m) {
  std::vector<float> out;
  for (int p = 0; p < kParamCount; ++p) {
    for (const Buffer<float>* b : {&m.tensor(Param(p)).value, &m.tensor(Param(p)).adam_m, &m.tensor(Param(p)).adam_v}) {
      const auto h = b->to_host();
      out.insert(out.end(), h.begin(), h.end());
    }
  }
  return out;
}

// The diffuse channel against the SH colour's view-independent part, C0 x DC + 1/2 clamped inside (0, 1),
// per Gaussian and channel (the model on the CPU); returns the largest error and the mean distance of the
// channel from the initial grey (so that a test can also check it is not flat).
struct DiffuseVsSh {
  double max_error = 0, mean_from_grey = 0;
};
inline DiffuseVsSh diffuse_vs_sh_colour(GaussianModel& m) {
  const float* sh = m.values(Param::Sh);
  const GaussianView v = m.view(true);
  const std::size_t sw = std::size_t(param_width(Param::Sh));
  DiffuseVsSh out;
  for (std::size_t i = 0; i < m.count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double col = std::clamp(0.28209479177387814 * double(sh[i * sw + std::size_t(c)]) + 0.5, 1e-3, 1 - 1e-3);
      const double d = v.extras[i * extra::kCount + std::size_t(extra::kDiffuse + c)];
      out.max_error = std::max(out.max_error, std::abs(d - col));
      out.mean_from_grey += std::abs(d - 0.5);
    }
  if (m.count() > 0) out.mean_from_grey /= double(3 * m.count());
  return out;
}

}  // namespace goris::test
