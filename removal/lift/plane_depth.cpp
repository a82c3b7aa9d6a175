#include "removal/lift/plane_depth.h"

#include <cmath>

#include "core/util/error.h"

namespace goris {

std::size_t depth_onto_plane(Image& depth, const Camera& camera, const Mask& where, const MirrorPlane& plane) {
  const int W = camera.width, H = camera.height;
  if (depth.width != W || depth.height != H || depth.channels != 1 || where.width != W || where.height != H)
    throw Error("depth onto the glossy plane", "the depth map or the mask is not the camera's size");
  const glm::dvec3 o(camera.center());
  std::size_t set = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t p = std::size_t(y) * W + x;
      if (!where.data[p]) continue;
      const glm::dvec3 d(camera.ray_direction(float(x) + 0.5f, float(y) + 0.5f));
      const double den = glm::dot(plane.normal, d);
      if (std::fabs(den) < 1e-9) continue;
      const double t = (plane.offset - glm::dot(plane.normal, o)) / den;
      if (!(t > 0)) continue;
      const float z = camera.to_camera(glm::vec3(o + t * d)).z;
      if (depth.pixels[p] < z) depth.pixels[p] = z, ++set;
    }
  return set;
}

}  // namespace goris
