// The main light of an environment (removal/shadow/environment_light.h): a bright lamp in a dim, noisy
// environment comes back as a direction and a place on the environment's sphere; what lies under the support
// surface is not a light for it; a black environment has none; a wrongly sized image is an error.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "removal/shadow/environment_light.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 pixel_direction(int i, int j, int width) {
  const int height = width / 2;
  const double t = kPi * (j + 0.5) / height, p = 2.0 * kPi * (i + 0.5) / width - kPi;
  return {std::sin(t) * std::sin(p), std::cos(t), std::sin(t) * std::cos(p)};
}

// A dim grey environment with noise, and lamps: (direction, angular radius in degrees, radiance).
struct Lamp {
  glm::dvec3 direction;
  double radius_degrees, radiance;
};
EnvironmentImage environment_with(const std::vector<Lamp>& lamps, double ambient = 0.3, int width = 256) {
  EnvironmentImage env;
  env.width = width;
  env.equirect.resize(std::size_t(width) * std::size_t(width / 2) * 3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> noise(0.0f, 0.6f);
  for (int j = 0; j < width / 2; ++j)
    for (int i = 0; i < width; ++i) {
      const glm::dvec3 d = pixel_direction(i, j, width);
      double v = ambient * noise(rng);
      for (const Lamp& l : lamps)
        if (glm::dot(d, glm::normalize(l.direction)) > std::cos(l.radius_degrees * kPi / 180.0)) v = l.radiance;
      for (int c = 0; c < 3; ++c) env.equirect[(std::size_t(j) * width + i) * 3 + c] = float(v);
    }
  return env;
}

double degrees_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180.0 / kPi;
}

TEST(EnvironmentLight, TheLampAboveTheSurface) {
  const glm::dvec3 up(0.0, 0.0, 1.0), lamp = glm::normalize(glm::dvec3(0.3, 0.35, 0.9));
  // A brighter lamp under the surface (seen in its reflection, not lighting it) and a dimmer one above.
  EnvironmentImage env = environment_with({{lamp, 8.0, 20.0}, {{0.2, -0.3, -0.9}, 8.0, 50.0}, {{-0.9, 0.1, 0.4}, 8.0, 4.0}});
  const EnvironmentLight at_infinity = environment_light(env, up);
  ASSERT_TRUE(at_infinity.found);
  EXPECT_LT(degrees_between(at_infinity.direction, lamp), 2.0);
  EXPECT_TRUE(at_infinity.at_infinity);
  EXPECT_EQ(at_infinity.direction_from(glm::dvec3(5.0, 1.0, 0.0)), at_infinity.direction);

  env.centre = {0.5, 0.0, 0.2};
  env.radius = 5.0;
  const EnvironmentLight on_sphere = environment_light(env, up);
  ASSERT_TRUE(on_sphere.found);
  EXPECT_FALSE(on_sphere.at_infinity);
  const glm::dvec3 expected = env.centre + 5.0 * on_sphere.direction;
  EXPECT_NEAR(glm::length(on_sphere.position - expected), 0.0, 1e-9);
  // From a point on the table the lamp's place is seen along its own direction, not the sphere's.
  const glm::dvec3 x(1.0, -1.0, 0.0);
  EXPECT_NEAR(glm::length(on_sphere.direction_from(x) - glm::normalize(expected - x)), 0.0, 1e-9);
  EXPECT_GT(degrees_between(on_sphere.direction_from(x), on_sphere.direction), 5.0);

  // Turned over (the surface's other side faces up), the lamp under it is the light.
  const EnvironmentLight other_side = environment_light(env, -up);
  ASSERT_TRUE(other_side.found);
  EXPECT_LT(degrees_between(other_side.direction, glm::dvec3(0.2, -0.3, -0.9)), 2.0);
}

TEST(EnvironmentLight, NoneInTheDarkAndBadInput) {
  EXPECT_FALSE(environment_light(environment_with({}, 0.0), {0.0, 0.0, 1.0}).found);
  EnvironmentImage bad = environment_with({}, 0.3, 64);
  bad.width = 60;
  test::expect_error([&] { environment_light(bad, {0.0, 0.0, 1.0}); }, "is not 60 x 30 x 3");
}

}  // namespace
}  // namespace goris
