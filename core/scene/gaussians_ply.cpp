// Conversion between the scene model and the PLY layout (core/io/ply.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/io/ply.h"
#include "core/scene/sh_layout.h"
#include "core/scene/gaussian_kernels.h"
#include "core/scene/gaussians.h"

namespace goris {

GaussianModel GaussianModel::from_ply(const GaussianPly& ply, Device device, const GaussianInit& init) {
  ply.check_consistent("PLY");
  const size_t n = ply.count;
  GaussianModel m(Device::CPU);
  m.allocate(n);
  m.max_sh_degree = 3;
  m.sh_degree = ply.sh_degree;
  std::copy(ply.positions.begin(), ply.positions.end(), m.values(Param::Position));
  std::copy(ply.scales.begin(), ply.scales.end(), m.values(Param::LogScale));
  std::copy(ply.rotations.begin(), ply.rotations.end(), m.values(Param::Rotation));
  std::copy(ply.opacity.begin(), ply.opacity.end(), m.values(Param::OpacityLogit));
  const std::vector<float> sh = sh_to_engine_layout(ply);
  std::copy(sh.begin(), sh.end(), m.values(Param::Sh));
  const float defaults[extra::kCount] = {init.diffuse, init.diffuse,   init.diffuse, init.fresnel, init.fresnel,
                                         init.fresnel, init.roughness, init.region,  init.label};
  float* ex = m.values(Param::ExtraLogit);
  for (int c = 0; c < extra::kCount; ++c) {
    const std::vector<float>* col = ply.extra(extra::kPlyNames[c]);
    const float fallback = kernels::logit(defaults[c]);
    for (size_t i = 0; i < n; ++i) ex[i * extra::kCount + c] = col ? (*col)[i] : fallback;
  }
  // A standard 3DGS PLY has no diffuse channel: show its view-independent colour rather than flat grey.
  if (!ply.extra(extra::kPlyNames[extra::kDiffuse])) m.derive_diffuse_from_sh();
  return device == Device::CPU ? std::move(m) : m.copy_to(device);
}

GaussianPly GaussianModel::to_ply(bool bake_3d_filter) const {
  GaussianPly ply;
  ply.count = count_;
  ply.sh_degree = max_sh_degree;
  ply.positions = tensor(Param::Position).value.to_host();
  ply.normals.assign(count_ * 3, 0.0f);
  ply.scales = tensor(Param::LogScale).value.to_host();
  ply.rotations = tensor(Param::Rotation).value.to_host();
  ply.opacity = tensor(Param::OpacityLogit).value.to_host();
  if (bake_3d_filter && filter3d_var.size() == count_) {
    const std::vector<float> var = filter3d_var.to_host();
    for (size_t i = 0; i < count_; ++i) {
      double det_ratio = 1;
      for (int a = 0; a < 3; ++a) {
        float& ls = ply.scales[i * 3 + a];
        const double s2 = std::exp(2.0 * double(ls)), s2f = s2 + double(var[i]);
        det_ratio *= s2 / s2f;
        ls = float(0.5 * std::log(s2f));
      }
      const double o = kernels::sigmoid(double(ply.opacity[i])) * std::sqrt(det_ratio);
      ply.opacity[i] = float(std::log(o / (1.0 - o)));
    }
  }
  const std::vector<float> sh = tensor(Param::Sh).value.to_host();
  sh_from_engine_layout(sh, ply);
  const std::vector<float> ex = tensor(Param::ExtraLogit).value.to_host();
  for (int c = 0; c < extra::kCount; ++c) {
    std::vector<float> col(count_);
    for (size_t i = 0; i < count_; ++i) col[i] = ex[i * extra::kCount + c];
    ply.extras.emplace_back(extra::kPlyNames[c], std::move(col));
  }
  return ply;
}

}  // namespace goris
