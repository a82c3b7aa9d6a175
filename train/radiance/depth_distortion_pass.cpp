#include "train/radiance/depth_distortion_pass.h"

#include <vector>

#include "core/compute/buffer.h"
#include "core/compute/host_device_image.h"
#include "core/compute/memory.h"

namespace goris {

double depth_distortion_pass(const GaussianView& gaussians, const Camera& camera, const RasterSettings& settings,
                             const DistortionDepthRange& range, float weight, const float* pixel_weight,
                             const GaussianGradView& grads, Device device) {
  const std::size_t n = std::size_t(gaussians.count);
  if (n == 0) return 0.0;
  const HostView positions(gaussians.positions, 3 * n, device);  // no copy on the CPU
  const float center = distortion_center(positions.data(), n, camera, range);
  std::vector<float> moments(2 * n);
  distortion_moments(positions.data(), n, camera, range, center, moments.data());
  const DeviceGrad moments_dev(moments, device);

  GaussianView v = gaussians;  // same geometry, SH DC only, the moments as the extra channels
  v.sh_degree = 0;
  v.extras = moments_dev.data();
  v.n_extras = 2;
  RasterSettings s = settings;
  s.profile = false;
  const RasterOutput r = rasterize(v, camera, s, device);

  const std::size_t hw = r.gbuffer.pixels();
  const HostView A(r.gbuffer.alpha.data(), hw, device), M(r.gbuffer.extras.data(), 2 * hw, device);  // M: [2][H][W]
  std::vector<float> gA(hw, 0.0f), gM(2 * hw, 0.0f);
  const double loss = depth_distortion_loss(A.data(), M.data(), M.data() + hw, hw, gA.data(), gM.data(),
                                            gM.data() + hw, weight, pixel_weight);
  if (weight == 0.0f) return loss;

  const DeviceGrad gA_dev(gA, device), gM_dev(gM, device);
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

  if (!grads.positions) return loss;
  // The centres' depth through (d, d^2): in place on the CPU, a round trip for a device's gradients.
  const HostView g_mom(g_moments.data(), 2 * n, device);
  if (device == Device::CPU) {
    distortion_moments_backward(positions.data(), n, camera, range, center, g_mom.data(), grads.positions);
  } else {
    std::vector<float> gp(3 * n);
    device_copy(gp.data(), Device::CPU, grads.positions, device, gp.size() * sizeof(float));
    distortion_moments_backward(positions.data(), n, camera, range, center, g_mom.data(), gp.data());
    device_copy(grads.positions, device, gp.data(), Device::CPU, gp.size() * sizeof(float));
  }
  return loss;
}

}  // namespace goris
