// Picking reuses the tracer's pieces directly (prims, Embree collector, blend_rounds) rather than
// GaussianTracer::trace, because the tracer returns only blended sums and picking needs the per-hit weights.
#include "removal/selection/selection_pick.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/trace/embree_accel.h"
#include "render/trace/trace_build.h"
#include "render/trace/trace_cpu.h"

namespace goris {

using namespace goris::trace;

struct GaussianPicker::Impl {
  PickSettings settings;
  std::size_t count = 0;
  std::vector<float> positions, log_scales, rotations, opacity_logits, filter3d;
  PrimData prims;
  EmbreeAccel accel;

  // blend_rounds gathers hits in rounds of this many (as the tracer's default).
  static constexpr int kRound = 128;

  PickResult trace(const glm::vec3& origin, const glm::vec3& dir_unit, float t_min) const {
    PickResult r;
    if (count == 0) return r;
    DenormalsOff ftz;
    const int cap = round_capacity(kRound, int(count));
    HitScratch<float> scratch(cap);
    HitList<float> list = scratch.list();
    auto collect = accel.collector(prims.prims.data());
    float best = -1.0f;
    const float T = blend_rounds(origin, dir_unit, t_min, RoundStart<float>{t_min, kNoId}, 1.0f, list, collect,
                                 [&](int i, float tr) {
                                   const float w = list.alpha[i] * tr;
                                   ++r.blended;
                                   if (w > best) {  // strict: among equal weights the front-most wins
                                     best = w;
                                     r.gaussian = list.id[i];
                                     r.distance = list.t[i];
                                   }
                                 });
    r.ray_alpha = 1.0f - T;
    r.weight = std::max(best, 0.0f);
    r.hit = r.blended > 0 && best >= settings.min_weight;
    r.point = origin + r.distance * dir_unit;
    r.depth = r.distance;
    return r;
  }
};

namespace {

bool finite_all(const float* p, int n) {
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(p[k])) return false;
  return true;
}

}  // namespace

GaussianPicker::GaussianPicker(const GaussianModel& model, const PickSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (!(settings.min_weight >= 0.0f && settings.min_weight <= 1.0f))
    throw Error("pick", "min_weight " + std::to_string(settings.min_weight) + " is outside [0, 1]");
  m.settings = settings;
  m.count = model.count();
  m.positions = model.tensor(Param::Position).value.to_host();
  m.log_scales = model.tensor(Param::LogScale).value.to_host();
  m.rotations = model.tensor(Param::Rotation).value.to_host();
  m.opacity_logits = model.tensor(Param::OpacityLogit).value.to_host();
  if (model.filter3d_var.size() == m.count && m.count > 0) m.filter3d = model.filter3d_var.to_host();
  for (std::size_t i = 0; i < m.count; ++i) {
    const float* q = &m.rotations[4 * i];
    if (!finite_all(&m.positions[3 * i], 3) || !finite_all(&m.log_scales[3 * i], 3) || !finite_all(q, 4) ||
        !std::isfinite(m.opacity_logits[i]) || (q[0] == 0.0f && q[1] == 0.0f && q[2] == 0.0f && q[3] == 0.0f) ||
        (!m.filter3d.empty() && !(m.filter3d[i] >= 0.0f && std::isfinite(m.filter3d[i]))))
      throw Error("pick", "Gaussian " + std::to_string(i) +
                              " has a non-finite parameter, a zero quaternion or a negative 3D filter variance");
  }
  if (m.count == 0) return;
  GaussiansT<float> g;
  g.count = int(m.count);
  g.positions = m.positions.data();
  g.log_scales = m.log_scales.data();
  g.rotations = m.rotations.data();
  g.opacity_logits = m.opacity_logits.data();
  g.filter3d_var = m.filter3d.empty() ? nullptr : m.filter3d.data();
  build_prims<Device::CPU>(g, m.prims);
  m.accel.build(m.prims.lo.data(), m.prims.hi.data(), m.count, false);
}

GaussianPicker::~GaussianPicker() = default;
GaussianPicker::GaussianPicker(GaussianPicker&&) noexcept = default;
GaussianPicker& GaussianPicker::operator=(GaussianPicker&&) noexcept = default;

std::size_t GaussianPicker::count() const { return impl_->count; }

PickResult GaussianPicker::pick(const Camera& camera, float u, float v) const {
  if (camera.width <= 0 || camera.height <= 0 || !(camera.fx > 0.0f) || !(camera.fy > 0.0f))
    throw Error("pick", "invalid camera (size or focal length)");
  if (!(u >= 0.0f && u < float(camera.width) && v >= 0.0f && v < float(camera.height)))
    throw Error("pick", "pixel (" + std::to_string(u) + ", " + std::to_string(v) + ") is outside the " +
                            std::to_string(camera.width) + "x" + std::to_string(camera.height) + " image");
  const glm::vec3 o = camera.center();
  const glm::vec3 d = camera.ray_direction(u, v);
  PickResult r = impl_->trace(o, d, 0.0f);
  r.depth = r.distance * glm::dot(d, camera.forward());
  return r;
}

PickResult GaussianPicker::pick_ray(const glm::vec3& origin, const glm::vec3& direction) const {
  const float len = glm::length(direction);
  if (!finite_all(&origin.x, 3) || !finite_all(&direction.x, 3) || !(len > 0.0f))
    throw Error("pick", "ray with a non-finite origin or a zero / non-finite direction");
  return impl_->trace(origin, direction / len, 0.0f);
}

PickResult pick_gaussian(const GaussianModel& model, const Camera& camera, int x, int y, const PickSettings& settings) {
  return GaussianPicker(model, settings).pick(camera, float(x) + 0.5f, float(y) + 0.5f);
}

}  // namespace goris
