#include "removal/shadow/environment_light.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/error.h"

namespace goris {

glm::dvec3 EnvironmentLight::direction_from(const glm::dvec3& x) const {
  if (at_infinity) return direction;
  const glm::dvec3 d = position - x;
  const double len = glm::length(d);
  return len > 1e-12 ? d / len : direction;
}

EnvironmentLight environment_light(const EnvironmentImage& env, const glm::dvec3& up_in,
                                   const EnvironmentLightSettings& st) {
  const std::vector<float>& eq = env.equirect;
  const int width = env.width, height = width / 2;
  if (width < 2 || eq.size() != std::size_t(width) * std::size_t(height) * 3)
    throw Error("environment light", "an equirectangular image of " + std::to_string(eq.size()) +
                                         " floats is not " + std::to_string(width) + " x " + std::to_string(height) + " x 3");
  const glm::dvec3 up = glm::normalize(up_in);
  const double pi = 3.14159265358979323846;
  // Per pixel: its direction and its radiance times its solid angle (sin t), 0 below the lowest elevation.
  struct Texel {
    glm::dvec3 d;
    double power = 0.0, area = 0.0;
  };
  std::vector<Texel> t(std::size_t(width) * std::size_t(height));
  double total_area = 0.0;
  for (int j = 0; j < height; ++j) {
    const double th = pi * (j + 0.5) / height;
    for (int i = 0; i < width; ++i) {
      const double ph = 2.0 * pi * (i + 0.5) / width - pi;
      Texel& x = t[std::size_t(j) * width + i];
      x.d = {std::sin(th) * std::sin(ph), std::cos(th), std::sin(th) * std::cos(ph)};
      if (glm::dot(x.d, up) < st.min_elevation) continue;
      const float* c = &eq[(std::size_t(j) * width + i) * 3];
      const double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
      x.area = std::sin(th);
      x.power = std::max(0.0, lum) * x.area;
      total_area += x.area;
    }
  }
  // The brightest texels (by radiance) until they cover top_fraction of the solid angle above the surface.
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k].area > 0.0) order.push_back(k);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return t[a].power / t[a].area > t[b].power / t[b].area; });
  EnvironmentLight out;
  glm::dvec3 sum(0.0);
  double area = 0.0;
  for (std::size_t k : order) {
    if (area >= st.top_fraction * total_area || !(t[k].power > 0.0)) break;
    sum += t[k].power * t[k].d;
    area += t[k].area;
  }
  if (!(glm::length(sum) > 0.0)) return out;
  out.found = true;
  out.direction = glm::normalize(sum);
  out.at_infinity = !(env.radius > 0.0);
  out.position = out.at_infinity ? glm::dvec3(0.0) : env.centre + env.radius * out.direction;
  return out;
}

}  // namespace goris
