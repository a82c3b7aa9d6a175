#pragma once
// Every value of a model and its Adam moments, flattened on the host: two trainings that should agree bit
// for bit compare these with EXPECT_EQ.
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

}  // namespace goris::test
