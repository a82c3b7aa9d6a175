#pragma once
// Spherical-harmonics coefficients between a PLY file's layout (f_dc, and f_rest channel-major up to the
// file's degree) and the engine's coefficient-major layout [N][16][3] (core/scene/gaussian_view.h).
#include <span>
#include <vector>

#include "core/io/ply.h"

namespace goris {

// SH coefficients in the engine's coefficient-major layout [N][16][3] (kMaxShCoeffs):
// k = 0 is f_dc, k >= 1 comes from f_rest; coefficients above sh_degree are zero.
std::vector<float> sh_to_engine_layout(const GaussianPly& ply);
// The inverse: fills ply.f_dc and ply.f_rest from `sh` ([count][16][3]) using ply.count and
// ply.sh_degree; coefficients above sh_degree are dropped.
void sh_from_engine_layout(std::span<const float> sh, GaussianPly& ply);

}  // namespace goris
