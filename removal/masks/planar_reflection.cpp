#include "removal/masks/planar_reflection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "core/util/error.h"
#include "removal/masks/inpaint_mask_scene.h"
#include "render/raster/rasterizer.h"

namespace goris {

GaussianModel mirrored_through(const GaussianModel& model, const SelectionMask& selected, const MirrorPlane& plane) {
  if (selected.size() != model.count())
    throw Error("planar reflection", "the selection has " + std::to_string(selected.size()) + " entries for " +
                                         std::to_string(model.count()) + " Gaussians");
  // Only what stands on the target's side of the surface is reflected by it (see the header).
  const std::vector<float> all_pos = model.tensor(Param::Position).value.to_host();
  SelectionMask in_front(selected.size(), 0);
  for (std::size_t i = 0; i < selected.size(); ++i) {
    const glm::dvec3 centre(all_pos[3 * i], all_pos[3 * i + 1], all_pos[3 * i + 2]);
    in_front[i] = selected[i] && plane.signed_distance(centre) > 0.0 ? 1 : 0;
  }
  GaussianModel m = subset_model(model, in_front);
  std::vector<float> pos = m.tensor(Param::Position).value.to_host();
  std::vector<float> rot = m.tensor(Param::Rotation).value.to_host();
  const glm::dvec3 n = glm::normalize(plane.normal);
  const glm::mat3 mirror = glm::mat3(1.0f) - 2.0f * glm::outerProduct(glm::vec3(n), glm::vec3(n));
  const glm::mat3 flip_z(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1));
  for (std::size_t i = 0; i < m.count(); ++i) {
    const glm::dvec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    const glm::dvec3 q = p - 2.0 * plane.signed_distance(p) * n;
    for (int k = 0; k < 3; ++k) pos[3 * i + k] = float(q[k]);
    glm::quat r(rot[4 * i], rot[4 * i + 1], rot[4 * i + 2], rot[4 * i + 3]);  // w, x, y, z
    const float len = glm::length(r);
    if (!(len > 0.0f) || !std::isfinite(len)) continue;
    // Covariance R S^2 R^T -> M R S^2 R^T M^T = (M R F) S^2 (M R F)^T with F = diag(1, 1, -1): M R F is a
    // rotation again (det +1) and F commutes with the diagonal S^2.
    const glm::quat mirrored = glm::quat_cast(mirror * glm::mat3_cast(r / len) * flip_z);
    rot[4 * i] = mirrored.w, rot[4 * i + 1] = mirrored.x, rot[4 * i + 2] = mirrored.y, rot[4 * i + 3] = mirrored.z;
  }
  m.tensor(Param::Position).value.upload(pos.data(), pos.size());
  m.tensor(Param::Rotation).value.upload(rot.data(), rot.size());
  return m;
}

Mask planar_reflection_mask(GaussianModel& mirrored, const Camera& camera, const std::vector<float>& glossy_mask,
                            const RasterSettings& raster, const ReflectionMaskSettings& settings) {
  const int w = camera.width, h = camera.height;
  if (glossy_mask.size() != std::size_t(w) * h)
    throw Error("planar reflection mask", "the glossy mask is not the camera's size");
  Mask covered(w, h);
  if (mirrored.count() > 0) {
    const RasterOutput r = rasterize(mirrored.view(false), camera, raster, mirrored.device());
    const std::vector<float> alpha = r.gbuffer.alpha.to_host();
    for (std::size_t p = 0; p < covered.data.size(); ++p)
      covered.data[p] = alpha[p] > settings.alpha_threshold && glossy_mask[p] > 0.5f ? 255 : 0;
  }
  const int grow = std::max(1, int(std::lround(settings.grow_fraction * float(w))));
  Mask grown = dilate_mask(covered, grow);
  for (std::size_t p = 0; p < grown.data.size(); ++p)
    if (glossy_mask[p] <= 0.5f) grown.data[p] = 0;
  return grown;
}

}  // namespace goris
