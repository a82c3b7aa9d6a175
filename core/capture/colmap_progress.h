#pragma once
// Progress of a COLMAP stage from the lines it prints as it goes:
//   feature_extractor   "Processed file [i/N]"
//   exhaustive_matcher  "Matching block [a/A, b/B]"   (A x B blocks)
//   sequential_matcher  "Matching image [i/N]"
//   mapper              "Registering image #k (n)"     (n images registered so far, out of the input's)
//   image_undistorter   "Undistorting image [i/N]"
#include <optional>
#include <string>

namespace goris::capture {

struct StageCount {
  int done = 0, total = 0;
};

// The count a line reports, or nothing for the other lines. `images` is the number of input images (the
// mapper's total).
std::optional<StageCount> parse_colmap_progress(const std::string& line, int images);

}  // namespace goris::capture
