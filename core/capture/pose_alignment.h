#pragma once
// How well a capture's camera poses agree with given ones (the poses that came with a data set): the
// camera centres of the views both have (matched by image name) are aligned by the similarity transform
// (scale, rotation, translation) that fits them best in the least-squares sense (Umeyama 1991), and the
// remaining distances are measured against the scene extent (the largest distance between two given
// centres, approximated by twice the largest distance from their mean).
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/dataset.h"

namespace goris::capture {

struct Similarity {
  double scale = 1;
  glm::dmat3 rotation{1.0};
  glm::dvec3 translation{0.0};
  glm::dvec3 apply(const glm::dvec3& p) const { return scale * (rotation * p) + translation; }
};

// The similarity that maps `from` onto `to` (same size, at least 3 points not on one line) best.
Similarity fit_similarity(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to);

struct PoseComparison {
  int matched = 0;          // views in both data sets
  int given = 0;            // views of the given data set
  double extent = 0;        // scene extent of the given centres
  double mean_error = 0;    // mean centre distance after alignment, as a fraction of the extent
  double max_error = 0;     // the largest
  double mean_angle_deg = 0;  // mean angle between the aligned viewing directions
  Similarity alignment;
};

// Compares the cameras of `captured` with those of `given` (train and test views of each). Throws
// goris::Error naming `given_name` when fewer than 3 image names are in both.
PoseComparison compare_poses(const Dataset& captured, const Dataset& given, const std::string& given_name);

std::string comparison_text(const PoseComparison& c);

}  // namespace goris::capture
