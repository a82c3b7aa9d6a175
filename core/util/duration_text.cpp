#include "core/util/duration_text.h"

#include <cstdio>

namespace goris {

std::string duration_text(double s) {
  if (!(s >= 0) || s > 1e8) return "--";
  const long t = long(s + 0.5);
  char b[32];
  if (t >= 3600)
    std::snprintf(b, sizeof b, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(b, sizeof b, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(b, sizeof b, "%lds", t);
  return b;
}

}  // namespace goris
