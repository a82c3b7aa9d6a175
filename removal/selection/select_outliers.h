#pragma once
// Outliers among selected Gaussian centres, so that a few stray labelled Gaussians (label noise, floaters)
// do not blow up the volume a selection is closed with. Two rules, both on the k-nearest-neighbour graph
// of the selected centres only:
//   1. statistical outlier removal: m_i = mean distance to the k nearest selected centres; an outlier has
//      m_i > max(mean(m) + std_ratio * std(m), min_ratio * mean(m)) (isolated single Gaussians). The
//      relative floor matters for near-uniform sets: there std(m) is tiny and the plain rule would flag
//      every point at a corner or a seam that is only a few percent farther from its neighbours;
//   2. small groups: link centres closer than that same bound (the largest "normal" neighbour distance),
//      and call every connected group holding less than min_group_fraction of the largest group an outlier
//      (a stray cluster of k or more Gaussians passes rule 1, because its members are each other's
//      neighbours, but it is still far from the object).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace goris {

struct OutlierSettings {
  int k = 8;
  float std_ratio = 2.0f;
  float min_ratio = 1.5f;
  float min_group_fraction = 0.1f;  // 0 disables rule 2
};

struct OutlierResult {
  std::vector<std::uint8_t> outlier;  // per input point, 1 = outlier
  std::size_t isolated = 0;           // by rule 1
  std::size_t in_small_groups = 0;    // by rule 2
  float link_distance = 0.0f;         // the neighbour distance bound of both rules (0 when not computed)
};

// Sets with fewer than 4 points have no statistics: nothing is an outlier.
OutlierResult find_outliers(const std::vector<glm::vec3>& points, const OutlierSettings& settings = {});

}  // namespace goris
