#include "core/train/held_out_views.h"

#include <algorithm>

#include "core/compute/memory.h"
#include "core/train/image_losses.h"
#include "core/util/error.h"

namespace goris {

std::vector<std::uint32_t> held_out_view_indices(std::size_t n_views, int every) {
  if (every < 2) throw Error("densify_holdout_every must be at least 2 (every view held out leaves none to train on)");
  if (n_views < 2)
    throw Error("densify_stop adaptive: holding a view out needs at least two training views (this run has " +
                std::to_string(n_views) + "); use densify_stop=fixed");
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < n_views; i += std::size_t(every)) out.push_back(std::uint32_t(i));
  return out;
}

std::vector<std::uint32_t> epoch_views(std::size_t n_views, const std::vector<std::uint32_t>& excluded) {
  std::vector<std::uint32_t> out;
  out.reserve(n_views);
  for (std::size_t i = 0; i < n_views; ++i)
    if (std::find(excluded.begin(), excluded.end(), std::uint32_t(i)) == excluded.end()) out.push_back(std::uint32_t(i));
  return out;
}

double held_out_psnr(DifferentiableRenderer& renderer, GaussianModel& model, const std::vector<TrainView>& views,
                     const std::vector<std::uint32_t>& indices) {
  if (indices.empty()) throw Error("held-out PSNR: no held-out views");
  const GaussianView gv = model.view(renderer.wants_extras());
  double sum = 0;
  std::vector<float> host;
  for (const std::uint32_t i : indices) {
    if (i >= views.size()) throw Error("held-out PSNR: view index out of range");
    const TrainView& v = views[i];
    const RenderedImages r = renderer.forward(gv, v.camera);
    const std::size_t n = std::size_t(3) * v.camera.width * v.camera.height;
    if (r.width != v.camera.width || r.height != v.camera.height || v.image.size() != n)
      throw Error(v.name, "held-out render and photo sizes differ");
    const float* color = r.color;
    if (renderer.device() != Device::CPU) {
      host.resize(n);
      device_copy(host.data(), Device::CPU, r.color, renderer.device(), n * sizeof(float));
      color = host.data();
    }
    sum += std::min(psnr_from_mse(mse<float>(color, v.image.data(), n)), 99.0);
  }
  return sum / double(indices.size());
}

}  // namespace goris
