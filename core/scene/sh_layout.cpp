#include "core/scene/sh_layout.h"

#include <string>

#include "core/scene/gaussian_view.h"
#include "core/util/error.h"

namespace goris {

std::vector<float> sh_to_engine_layout(const GaussianPly& ply) {
  ply.check_consistent("sh_to_engine_layout");
  const size_t rest = GaussianPly::rest_per_gaussian(ply.sh_degree) / 3;  // coefficients k >= 1 per channel
  std::vector<float> sh(ply.count * kMaxShCoeffs * 3, 0.0f);
  for (size_t i = 0; i < ply.count; ++i) {
    float* dst = &sh[i * kMaxShCoeffs * 3];
    const float* src = &ply.f_rest[i * rest * 3];
    for (int c = 0; c < 3; ++c) {
      dst[c] = ply.f_dc[i * 3 + c];
      for (size_t k = 1; k <= rest; ++k) dst[k * 3 + c] = src[size_t(c) * rest + (k - 1)];
    }
  }
  return sh;
}

void sh_from_engine_layout(std::span<const float> sh, GaussianPly& ply) {
  if (ply.sh_degree < 0 || ply.sh_degree > 3)
    throw Error("sh_from_engine_layout", "SH degree " + std::to_string(ply.sh_degree) + " is outside 0..3");
  if (sh.size() != ply.count * kMaxShCoeffs * 3)
    throw Error("sh_from_engine_layout", "expected " + std::to_string(ply.count) + " x 16 x 3 SH values, got " +
                                             std::to_string(sh.size()));
  const size_t rest = GaussianPly::rest_per_gaussian(ply.sh_degree) / 3;
  ply.f_dc.resize(ply.count * 3);
  ply.f_rest.resize(ply.count * rest * 3);
  for (size_t i = 0; i < ply.count; ++i) {
    const float* src = &sh[i * kMaxShCoeffs * 3];
    float* dst = &ply.f_rest[i * rest * 3];
    for (int c = 0; c < 3; ++c) {
      ply.f_dc[i * 3 + c] = src[c];
      for (size_t k = 1; k <= rest; ++k) dst[size_t(c) * rest + (k - 1)] = src[k * 3 + c];
    }
  }
}

}  // namespace goris
