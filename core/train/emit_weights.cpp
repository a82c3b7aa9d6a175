#include "core/train/emit_weights.h"


namespace goris {

std::vector<float> glossy_mask_emit_weights(const GaussianModel& model, const std::vector<TrainView>& views) {
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::size_t n = model.count();
  std::vector<float> sum(n, 0.0f), count(n, 0.0f);
  for (const TrainView& v : views) {
    const Camera& c = v.camera;
    if (v.glossy_mask.size() != std::size_t(c.width) * std::size_t(c.height)) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const long long q = c.pixel_of(c.to_camera(glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2])));
      if (q < 0) continue;
      sum[i] += v.glossy_mask[std::size_t(q)];
      count[i] += 1.0f;
    }
  }
  std::vector<float> w(n, 1.0f);
  for (std::size_t i = 0; i < n; ++i)
    if (count[i] > 0) w[i] = 1.0f - sum[i] / count[i];
  return w;
}

}  // namespace goris
