#include "core/train/emit_weights.h"

#include <cmath>

namespace goris {

std::vector<float> glossy_mask_emit_weights(const GaussianModel& model, const std::vector<TrainView>& views) {
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::size_t n = model.count();
  std::vector<float> sum(n, 0.0f), count(n, 0.0f);
  for (const TrainView& v : views) {
    const Camera& c = v.camera;
    if (v.glossy_mask.size() != std::size_t(c.width) * std::size_t(c.height)) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const glm::vec3 p = c.to_camera(glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
      if (p.z <= 1e-6f) continue;
      const glm::vec2 uv = c.project_camera(p);
      const int x = int(std::floor(uv.x)), y = int(std::floor(uv.y));
      if (x < 0 || y < 0 || x >= c.width || y >= c.height) continue;
      sum[i] += v.glossy_mask[std::size_t(y) * std::size_t(c.width) + std::size_t(x)];
      count[i] += 1.0f;
    }
  }
  std::vector<float> w(n, 1.0f);
  for (std::size_t i = 0; i < n; ++i)
    if (count[i] > 0) w[i] = 1.0f - sum[i] / count[i];
  return w;
}

}  // namespace goris
