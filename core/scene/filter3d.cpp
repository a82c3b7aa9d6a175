#include "core/scene/filter3d.h"

#include <algorithm>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace goris {

void compute_filter3d(GaussianModel& model, const std::vector<Camera>& cameras) {
  const size_t n = model.count();
  if (n == 0 || cameras.empty()) {
    model.filter3d_var = Buffer<float>();
    return;
  }
  // Positions to the host (a copy only for a CUDA model); this runs once per densification step.
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  std::vector<float> rate(n, 0.0f);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const glm::vec3 x(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
      float best = 0.0f;
      for (const Camera& cam : cameras) {
        const glm::vec3 p = cam.to_camera(x);
        if (p.z <= 0.2f) continue;
        const glm::vec2 uv = cam.project_camera(p);
        const float w = float(cam.width), h = float(cam.height);
        if (uv.x < -0.15f * w || uv.x > 1.15f * w || uv.y < -0.15f * h || uv.y > 1.15f * h) continue;
        best = std::max(best, cam.fx / p.z);
      }
      rate[i] = best;
    }
  });
  float lowest_seen = std::numeric_limits<float>::max();
  for (float r : rate)
    if (r > 0) lowest_seen = std::min(lowest_seen, r);
  const bool none_seen = lowest_seen == std::numeric_limits<float>::max();
  std::vector<float> var(n);
  for (size_t i = 0; i < n; ++i) {
    float r = rate[i] > 0 ? rate[i] : lowest_seen;
    if (none_seen) {  // no camera sees any Gaussian: each one's nearest camera, ignoring the frustum
      r = 0;
      const glm::vec3 x(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
      for (const Camera& cam : cameras) r = std::max(r, cam.fx / std::max(1e-3f, glm::length(x - cam.center())));
    }
    var[i] = 0.2f / (r * r);
  }
  model.filter3d_var = Buffer<float>(var, model.device());
}

}  // namespace goris
