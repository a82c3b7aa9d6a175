#include "render/train/depth_distortion_pass.h"

#include <vector>

#include "core/compute/buffer.h"
#include "core/compute/memory.h"

namespace goris {

double depth_distortion_pass(const GaussianView& gaussians, const Camera& camera, const RasterSettings& settings,
                             const DistortionDepthRange& range, float weight, const GaussianGradView& grads,
                             Device device) {
  const std::size_t n = std::size_t(gaussians.count);
  if (n == 0) return 0.0;
  std::vector<float> positions(3 * n), moments(2 * n);
  device_copy(positions.data(), Device::CPU, gaussians.positions, device, positions.size() * sizeof(float));
  const float center = distortion_center(positions.data(), n, camera, range);
  distortion_moments(positions.data(), n, camera, range, center, moments.data());
  const Buffer<float> moments_dev(moments, device);

  GaussianView v = gaussians;  // same geometry, SH DC only, the moments as the extra channels
  v.sh_degree = 0;
  v.extras = moments_dev.data();
  v.n_extras = 2;
  RasterSettings s = settings;
  s.profile = false;
  const RasterOutput r = rasterize(v, camera, s, device);

  const std::size_t hw = r.gbuffer.pixels();
  const std::vector<float> A = r.gbuffer.alpha.to_host(), M = r.gbuffer.extras.to_host();  // M: [2][H][W]
  std::vector<float> gA(hw, 0.0f), gM(2 * hw, 0.0f);
  const double loss = depth_distortion_loss(A.data(), M.data(), M.data() + hw, hw, gA.data(), gM.data(),
                                            gM.data() + hw, weight);
  if (weight == 0.0f) return loss;

  const Buffer<float> gA_dev(gA, device), gM_dev(gM, device);
  Buffer<float> g_moments(2 * n, device);
  g_moments.fill_zero();
  GBufferGrad go;
  go.alpha = gA_dev.data();
  go.extras = gM_dev.data();
  GaussianGradView gg;
  gg.positions = grads.positions;
  gg.log_scales = grads.log_scales;
  gg.rotations = grads.rotations;
  gg.opacity_logits = grads.opacity_logits;
  gg.extras = g_moments.data();
  rasterize_backward(v, r.state, go, gg);

  if (grads.positions) {  // the centres' depth through (m, m^2)
    std::vector<float> gp(3 * n);
    device_copy(gp.data(), Device::CPU, grads.positions, device, gp.size() * sizeof(float));
    distortion_moments_backward(positions.data(), n, camera, range, center, g_moments.to_host().data(), gp.data());
    device_copy(grads.positions, device, gp.data(), Device::CPU, gp.size() * sizeof(float));
  }
  return loss;
}

}  // namespace goris
