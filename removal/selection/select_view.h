#pragma once
// A renderer's view of a const GaussianModel without extras (GaussianModel::view() is non-const because it
// may activate the extras into a scratch buffer).
#include "core/scene/gaussian_view.h"
#include "core/scene/gaussians.h"

namespace goris {

inline GaussianView plain_gaussian_view(const GaussianModel& m) {
  GaussianView v;
  v.count = int(m.count());
  v.positions = m.values(Param::Position);
  v.log_scales = m.values(Param::LogScale);
  v.rotations = m.values(Param::Rotation);
  v.opacity_logits = m.values(Param::OpacityLogit);
  v.sh = m.values(Param::Sh);
  v.sh_degree = m.sh_degree;
  v.filter3d_var = m.filter3d_var.size() == m.count() && m.count() > 0 ? m.filter3d_var.data() : nullptr;
  return v;
}

}  // namespace goris
