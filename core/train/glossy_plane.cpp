#include "core/train/glossy_plane.h"

#include <cmath>
#include <cstdio>

#include <glm/gtc/quaternion.hpp>

#include "core/compute/parallel_for.h"
#include "core/removal/selection_points.h"
#include "core/train/densify.h"
#include "core/train/trainer.h"

namespace goris {

std::vector<std::uint8_t> over_glossy_pixels(const GaussianModel& model, const std::vector<TrainView>& views) {
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::size_t n = model.count();
  std::vector<std::uint32_t> on_glossy(n, 0), in_frame(n, 0);
  for (const TrainView& v : views) {
    const Camera& c = v.camera;
    if (v.glossy_mask.size() != std::size_t(c.width) * std::size_t(c.height)) continue;
    parallel_for(Device::CPU, n, [&](std::size_t i) {
      const long long pixel = c.pixel_of(c.to_camera(glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2])));
      if (pixel < 0) return;
      ++in_frame[i];
      if (v.glossy_mask[std::size_t(pixel)] > 0.5f) ++on_glossy[i];
    }, 1024);
  }
  std::vector<std::uint8_t> over(n, 0);
  for (std::size_t i = 0; i < n; ++i) over[i] = 2 * on_glossy[i] > in_frame[i];
  return over;
}

MirrorPlane glossy_surface_plane(const GaussianModel& model, const std::vector<TrainView>& views,
                                 const std::vector<std::uint8_t>& over_glossy) {
  const SelectionPoints points = selection_points(model);
  const std::vector<glm::vec3> flat = flat_normals(model);
  std::vector<glm::vec3> centres, normals;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (over_glossy[i]) centres.push_back(points.position[i]), normals.push_back(flat[i]);
  MirrorPlane plane = fit_mirror_plane(centres, {}, normals);
  if (!plane.found) return plane;
  std::size_t above = 0, cameras = 0;
  for (const TrainView& v : views) above += plane.signed_distance(glm::dvec3(v.camera.center())) > 0, ++cameras;
  if (2 * above < cameras) plane.normal = -plane.normal, plane.offset = -plane.offset;
  return plane;
}

namespace {

// The flagged centres more than the plane's tolerance beyond it.
template <typename F>
void for_each_beyond(const std::vector<float>& pos, const MirrorPlane& plane, const std::vector<std::uint8_t>& flags,
                     F&& f) {
  for (std::size_t i = 0; i < flags.size(); ++i) {
    if (!flags[i]) continue;
    const glm::dvec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    const double d = plane.signed_distance(p);
    if (d < -plane.tolerance) f(i, p, d);
  }
}

}  // namespace

std::string GlossyPlaneConstraint::start(GaussianModel& model, const std::vector<TrainView>& views) {
  started_ = true;
  over_glossy_ = over_glossy_pixels(model, views);
  plane_ = glossy_surface_plane(model, views, over_glossy_);
  if (!plane_.found) return "glossy plane: none found, not constrained";
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  std::vector<std::uint8_t> keep(model.count(), 1);
  for_each_beyond(pos, plane_, over_glossy_, [&](std::size_t i, const glm::dvec3&, double) { keep[i] = 0; });
  const std::size_t before = model.count();
  pruned_ = prune_gaussians(model, keep);
  over_glossy_.clear();  // refreshed at the first apply()
  char buf[200];
  std::snprintf(buf, sizeof buf, "glossy plane n = (%.3f, %.3f, %.3f), n . x = %.3f (%zu of %zu centres): pruned %zu of %zu beyond it",
                plane_.normal.x, plane_.normal.y, plane_.normal.z, plane_.offset, plane_.inliers, plane_.glossy, pruned_,
                before);
  return buf;
}

GlossyPlaneConstraint::Step GlossyPlaneConstraint::apply(GaussianModel& model, const std::vector<TrainView>& views,
                                                         int it, bool prune_sinkers) {
  Step step;
  if (!plane_.found) return step;
  if (over_glossy_.size() != model.count() || it - refreshed_at_ >= kRefreshInterval) {
    if (prune_sinkers && sank_.size() == model.count()) {
      std::vector<std::uint8_t> keep(sank_.size());
      for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = !sank_[i];
      step.pruned = prune_gaussians(model, keep);
      sinkers_pruned_ += step.pruned;
    }
    over_glossy_ = over_glossy_pixels(model, views);
    sank_.assign(model.count(), 0);
    refreshed_at_ = it;
  }
  ParamTensor& t = model.tensor(Param::Position);
  std::vector<float> pos = t.value.to_host();
  for_each_beyond(pos, plane_, over_glossy_, [&](std::size_t i, const glm::dvec3& p, double d) {
    const glm::dvec3 q = p - (d + 0.5 * plane_.tolerance) * plane_.normal;  // inside the band, float-safe
    pos[3 * i] = float(q.x), pos[3 * i + 1] = float(q.y), pos[3 * i + 2] = float(q.z);
    sank_[i] = 1;
    ++step.moved;
  });
  if (step.moved) t.value.upload(pos.data(), pos.size());
  return step;
}

std::size_t GlossyPlaneConstraint::align_normals(GaussianModel& model) const {
  if (!plane_.found || over_glossy_.size() != model.count()) return 0;
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::vector<glm::vec3> flat = flat_normals(model);  // zero where a Gaussian is not flat
  ParamTensor& t = model.tensor(Param::Rotation);
  std::vector<float> rot = t.value.to_host();
  const glm::dvec3 n = plane_.normal;
  std::size_t turned = 0;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    if (!over_glossy_[i] || flat[i] == glm::vec3(0.0f)) continue;
    const glm::dvec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    if (std::abs(plane_.signed_distance(p)) > plane_.tolerance) continue;
    const glm::dvec3 a = glm::normalize(glm::dvec3(flat[i]));
    const glm::dvec3 target = glm::dot(a, n) < 0 ? -n : n;  // the nearer of the two sides
    const double c = glm::dot(a, target);
    if (c > 1.0 - 1e-12) continue;
    // The shortest rotation taking a to target, (1 + a.t, a x t) normalised, applied before the stored one;
    // the stored quaternion's length is kept (it is stored unnormalised, DESIGN.md §4).
    const glm::dvec3 axis = glm::cross(a, target);
    const glm::dquat turn = glm::normalize(glm::dquat(1.0 + c, axis.x, axis.y, axis.z));
    float* r = &rot[4 * i];
    const glm::dquat q(r[0], r[1], r[2], r[3]);
    const glm::dquat out = turn * q;
    r[0] = float(out.w), r[1] = float(out.x), r[2] = float(out.y), r[3] = float(out.z);
    ++turned;
  }
  if (turned) t.value.upload(rot.data(), rot.size());
  return turned;
}

}  // namespace goris
