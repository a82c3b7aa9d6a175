#pragma once
// How far one model is from another, attribute by attribute: what a lossy format (core/io/splat_formats.h)
// changed. Used by the format tests, the cross-checks with other software and `goris info --against`.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/io/ply.h"

namespace goris {

struct AttributeError {
  double max = 0, mean = 0;
  size_t worst = 0;  // the Gaussian (in `got`) with the largest error
};

struct ModelDiff {
  size_t count = 0;
  AttributeError position;  // Euclidean distance, world units
  AttributeError scale;     // largest |difference| of the three log scales
  // Largest angle between corresponding principal axes, degrees, each axis up to sign: q and -q, and the
  // half-turns about an axis that leave the ellipsoid unchanged, count as the same rotation.
  AttributeError rotation;
  AttributeError opacity;   // |difference| after the sigmoid
  AttributeError f_dc;      // largest |difference| of the three DC coefficients
  AttributeError f_rest;    // largest |difference| of the SH rest coefficients present in both (0 when none)
  std::string table() const;  // one line per attribute
};

// For each Gaussian of `got`, the Gaussian of `ref` nearest to it in position (for files whose writer
// reordered the Gaussians). Throws goris::Error when the counts differ.
std::vector<uint32_t> match_by_position(const GaussianPly& ref, const GaussianPly& got);

// Compares got[i] with ref[order[i]] (order empty: ref[i]). Throws goris::Error when the counts differ.
ModelDiff compare_models(const GaussianPly& ref, const GaussianPly& got, const std::vector<uint32_t>& order = {});

}  // namespace goris
