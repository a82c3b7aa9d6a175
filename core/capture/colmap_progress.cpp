#include "core/capture/colmap_progress.h"

#include <cstdio>

namespace goris::capture {

std::optional<StageCount> parse_colmap_progress(const std::string& line, int images) {
  int a = 0, b = 0, c = 0, d = 0;
  const char* s = line.c_str();
  while (*s == ' ') ++s;
  if (std::sscanf(s, "Processed file [%d/%d]", &a, &b) == 2) return StageCount{a, b};
  if (std::sscanf(s, "Undistorting image [%d/%d]", &a, &b) == 2) return StageCount{a, b};
  if (std::sscanf(s, "Matching image [%d/%d]", &a, &b) == 2) return StageCount{a, b};
  if (std::sscanf(s, "Matching block [%d/%d, %d/%d]", &a, &b, &c, &d) == 4 && b > 0 && d > 0)
    return StageCount{(a - 1) * d + c, b * d};
  if (std::sscanf(s, "Registering image #%d (%d)", &a, &b) == 2) return StageCount{b, images};
  return std::nullopt;
}

}  // namespace goris::capture
