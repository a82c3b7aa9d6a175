#pragma once
// A random model for the splat format tests (tests/unit/test_splat_formats.cpp, tests/crosscheck): every
// attribute inside the ranges the formats are designed for.
#include <cstdint>
#include <random>
#include <vector>

#include "core/io/splat_codec.h"

namespace goris::test {

// Positions within a 10-unit box, log scales -8..3, any rotation (unnormalised, either sign), opacity
// logits -6..6, DC -2..2, SH rest -0.9..0.9, and normals and two extra properties that the formats drop.
inline GaussianPly random_splat_model(size_t n, int degree, uint32_t seed) {
  std::mt19937 rng(seed);
  auto u = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  GaussianPly g = splat_detail::sized_model(n, degree);
  for (float& v : g.positions) v = u(-5, 5);
  for (float& v : g.scales) v = u(-8, 3);
  for (float& v : g.rotations) v = u(-2, 2);
  for (float& v : g.opacity) v = u(-6, 6);
  for (float& v : g.f_dc) v = u(-2, 2);
  for (float& v : g.f_rest) v = u(-0.9f, 0.9f);
  g.normals.assign(n * 3, 0.25f);
  g.extras.emplace_back("roughness", std::vector<float>(n, 0.5f));
  g.extras.emplace_back("label", std::vector<float>(n, 1.0f));
  return g;
}

}  // namespace goris::test
