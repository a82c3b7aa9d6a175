#pragma once
// Where an intrinsic model's environment says the main light is: the direction of its brightest region. The
// target's shadow fit (target_shadow.h) searches the whole sky for the light whose shadow explains the support
// surface's darkening best; where a light stands high above the target, most of its shadow lies under the
// target and the little that shows is outweighed by the surface's texture and baked reflections, so the
// search settles on a low, wrong light and rejects it. The learned environment map holds the light the
// reflections were lit by, which narrows the search to where a light actually is.
#include <vector>

#include <glm/glm.hpp>

namespace goris {

struct EnvironmentLight {
  bool found = false;
  glm::dvec3 direction{0.0, 0.0, 1.0};  // unit, from the environment's centre
  // The light's place on the environment's sphere (centre + radius * direction); an environment at infinity
  // (radius 0) has only a direction.
  glm::dvec3 position{0.0};
  bool at_infinity = true;
  // The unit direction from point x toward the light.
  glm::dvec3 direction_from(const glm::dvec3& x) const;
};

struct EnvironmentLightSettings {
  // The light is the radiance-weighted mean direction of this brightest share of the solid angle above the
  // surface (0.5 %: about 4 degrees across, the size of a room's lamp seen from a table, and enough texels at a
  // 256 x 128 preview that a single noisy texel cannot decide).
  double top_fraction = 0.005;
  double min_elevation = 0.05;  // sin of the lowest elevation above the surface a light may have
};

// An environment as the removal has it: the map's preview image and its sphere.
struct EnvironmentImage {
  // [width / 2][width][3] linear radiance in the layout of EnvironmentMap::equirect_image: pixel (i, j) looks
  // along (sin t sin p, cos t, sin t cos p), t = pi (j + 0.5) / h, p = 2 pi (i + 0.5) / width - pi.
  std::vector<float> equirect;
  int width = 0;
  glm::dvec3 centre{0.0};  // the environment's sphere (radius 0: at infinity)
  double radius = 0.0;
};

// up: the support surface's normal on the target's side. Not found when nothing above the surface is brighter
// than black. Throws goris::Error when the image's size is not width x width / 2 x 3.
EnvironmentLight environment_light(const EnvironmentImage& env, const glm::dvec3& up,
                                   const EnvironmentLightSettings& settings = {});

}  // namespace goris
