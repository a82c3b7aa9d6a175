#pragma once
// The CPU acceleration structure on Embree 3: one user geometry whose primitives are the Gaussians' boxes
// at the 1/255 response level. The intersect callback evaluates the Gaussian (trace_hit.h), records every
// hit in the ray's bounded, sorted hit list and reports nothing to Embree, so traversal goes on to every
// other candidate; once the list is full the ray's tfar shrinks to its farthest hit, which culls the rest.
#include <cstddef>
#include <memory>
#include <vector>

#include "render/trace/trace_ray.h"

namespace goris::trace {

class EmbreeAccel {
 public:
  EmbreeAccel();
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  // Builds (or, with allow_refit, an unchanged count and the same empty boxes as at the last build,
  // refits) over n boxes lo/hi [n][3] (host memory, copied). Returns true when it refitted.
  bool build(const float* lo, const float* hi, std::size_t n, bool allow_refit);

  // A collector (trace_ray.h) over `prims` (host memory, the same order as the boxes).
  struct Collector {
    const EmbreeAccel* accel;
    const TracePrim<float>* prims;
    void operator()(const Vec3<float>& o, const Vec3<float>& d, float t_min, RoundStart<float> start,
                    HitList<float>& l) const;
  };
  Collector collector(const TracePrim<float>* prims) const { return Collector{this, prims}; }

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace goris::trace
