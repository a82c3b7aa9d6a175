#include "train/loop/mirror_world.h"

#include <cmath>

#include "core/compute/host_device_image.h"
#include "core/compute/parallel_for.h"
#include "core/util/error.h"
#include "train/optimizer/densify.h"

namespace goris {

std::vector<std::uint8_t> find_mirror_world(const GaussianModel& model, const std::vector<TrainView>& views,
                                            const DepthAlphaRender& render, float tolerance, int min_views) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) throw Error("mirror world: the tolerance must be finite and >= 0");
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::size_t n = model.count();
  std::vector<std::uint32_t> behind(n, 0), seen(n, 0);
  std::vector<float> depth, alpha;
  for (const TrainView& v : views) {
    const Camera& c = v.camera;
    const std::size_t hw = std::size_t(c.width) * std::size_t(c.height);
    if (v.glossy_mask.size() != hw) continue;
    render(c, depth, alpha);
    if (depth.size() != hw || alpha.size() != hw) throw Error(v.name, "mirror world: the render does not match the view");
    parallel_for(Device::CPU, n, [&](std::size_t i) {
      const glm::vec3 p = c.to_camera(glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
      const long long pixel = c.pixel_of(p);
      if (pixel < 0) return;
      const std::size_t q = std::size_t(pixel);
      if (!(alpha[q] > 0.5f) || p.z <= depth[q] * (1.0f + tolerance))
        ++seen[i];
      else if (v.glossy_mask[q] > 0.5f)
        ++behind[i];
    }, 1024);
  }
  std::vector<std::uint8_t> mirror(n, 0);
  for (std::size_t i = 0; i < n; ++i) mirror[i] = seen[i] == 0 && behind[i] >= std::uint32_t(std::max(min_views, 1));
  return mirror;
}

size_t prune_mirror_world(GaussianModel& model, const std::vector<TrainView>& views, DifferentiableRenderer& renderer,
                          float tolerance) {
  const GaussianView view = model.view(renderer.wants_extras());
  const Device d = renderer.device();
  const std::vector<std::uint8_t> mirror = find_mirror_world(
      model, views,
      [&](const Camera& c, std::vector<float>& depth, std::vector<float>& alpha) {
        const RenderedImages r = renderer.forward(view, c);
        const size_t n = size_t(c.width) * size_t(c.height);
        const HostView z(r.median_depth, n, d), a(r.alpha, n, d);
        depth.assign(z.data(), z.data() + n), alpha.assign(a.data(), a.data() + n);
      },
      tolerance);
  std::vector<std::uint8_t> keep(mirror.size());
  for (size_t i = 0; i < keep.size(); ++i) keep[i] = !mirror[i];
  return prune_gaussians(model, keep);
}

}  // namespace goris
