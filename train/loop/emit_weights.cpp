#include "train/loop/emit_weights.h"

namespace goris {

namespace {

// Accumulates one view's mask values at the Gaussians' centres.
void add_view(const std::vector<float>& pos, const Camera& c, const std::vector<float>& mask, std::vector<float>& sum,
              std::vector<float>& count) {
  if (mask.size() != std::size_t(c.width) * std::size_t(c.height)) return;
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const long long q = c.pixel_of(c.to_camera(glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2])));
    if (q < 0) continue;
    sum[i] += mask[std::size_t(q)];
    count[i] += 1.0f;
  }
}

std::vector<float> weights(const std::vector<float>& sum, const std::vector<float>& count) {
  std::vector<float> w(sum.size(), 1.0f);
  for (std::size_t i = 0; i < w.size(); ++i)
    if (count[i] > 0) w[i] = 1.0f - sum[i] / count[i];
  return w;
}

}  // namespace

std::vector<float> glossy_mask_emit_weights(const std::vector<float>& positions, const std::vector<GlossyMaskView>& views) {
  const std::size_t n = positions.size() / 3;
  std::vector<float> sum(n, 0.0f), count(n, 0.0f);
  for (const GlossyMaskView& v : views) add_view(positions, v.camera, v.mask, sum, count);
  return weights(sum, count);
}

std::vector<float> glossy_mask_emit_weights(const GaussianModel& model, const std::vector<TrainView>& views) {
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  std::vector<float> sum(model.count(), 0.0f), count(model.count(), 0.0f);
  for (const TrainView& v : views) add_view(pos, v.camera, v.glossy_mask, sum, count);
  return weights(sum, count);
}

}  // namespace goris
