// The target's underside: what stands on the glossy surface inside the target's footprint and below its top is
// taken; what lies beside it, under the surface, above the target or is selected already is not.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "removal/selection/target_underside.h"

using namespace goris;

namespace {

// A ball of centres (radius 0.3, centre 0.35 above the plane z = 0), then the probes; `frame` moves all of it
// (and the plane) rigidly.
struct Scene {
  std::vector<glm::vec3> centres;
  SelectionMask target, selected;
  MirrorPlane plane;
};

Scene ball_with_probes(const std::vector<glm::vec3>& probes, const glm::mat4& frame, std::size_t twin_probe = size_t(-1)) {
  Scene s;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 10; ++j) {
      const double th = M_PI * (j + 0.5) / 10, ph = 2 * M_PI * i / 20;
      s.centres.push_back(glm::vec3(0.3 * std::sin(th) * std::cos(ph), 0.3 * std::sin(th) * std::sin(ph), 0.35 + 0.3 * std::cos(th)));
    }
  s.target.assign(s.centres.size(), 1);
  for (const glm::vec3& p : probes) s.centres.push_back(p), s.target.push_back(0);
  s.selected = s.target;
  if (twin_probe != size_t(-1)) s.selected[200 + twin_probe] = 1;
  for (glm::vec3& c : s.centres) c = glm::vec3(frame * glm::vec4(c, 1.0f));
  s.plane.found = true;
  s.plane.normal = glm::normalize(glm::dvec3(glm::mat3(frame) * glm::vec3(0, 0, 1)));
  s.plane.offset = glm::dot(s.plane.normal, glm::dvec3(glm::vec3(frame * glm::vec4(0, 0, 0, 1))));
  return s;
}

const std::vector<glm::vec3> kProbes = {
    {0.0f, 0.0f, 0.02f},   // 0: under the ball, on the surface: taken
    {0.1f, 0.05f, 0.2f},   // 1: inside the ball's lower half: taken
    {0.0f, 0.0f, -0.05f},  // 2: under the surface (the mirror world): not
    {0.5f, 0.0f, 0.1f},    // 3: beside the ball: not
    {0.0f, 0.0f, 0.9f},    // 4: above the target's top: not
    {0.0f, 0.0f, 0.0f},    // 5: exactly on the plane: not (above it only)
    {-0.05f, 0.0f, 0.05f}, // 6: under the ball but selected already (a twin): not again
};

}  // namespace

TEST(TargetUnderside, TakesWhatStandsUnderTheTargetOnly) {
  for (const glm::mat4& frame : {glm::mat4(1.0f), glm::translate(glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(1, 2, 0.5f)),
                                                                 glm::vec3(3, -1, 2))}) {
    const Scene s = ball_with_probes(kProbes, frame, 6);
    const SelectionMask under = target_underside(s.centres, s.target, s.selected, s.plane);
    ASSERT_EQ(under.size(), s.centres.size());
    for (std::size_t i = 0; i < 200; ++i) EXPECT_EQ(under[i], 0) << "a target centre is no underside";
    const int expected[] = {1, 1, 0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < kProbes.size(); ++k) EXPECT_EQ(under[200 + k], expected[k]) << "probe " << k;
  }
}

TEST(TargetUnderside, FootprintIsAShareOfTheTargetsRadius) {
  // The ball's 90 % radius is close to 0.3 (its equator ring); a probe at 0.25 from the axis is outside 0.7 of
  // it and inside all of it.
  const Scene s = ball_with_probes({{0.25f, 0.0f, 0.05f}, {0.15f, 0.0f, 0.05f}}, glm::mat4(1.0f));
  const SelectionMask narrow = target_underside(s.centres, s.target, s.selected, s.plane);
  EXPECT_EQ(narrow[200], 0);
  EXPECT_EQ(narrow[201], 1);
  UndersideSettings wide;
  wide.radius_ratio = 1.0;
  EXPECT_EQ(target_underside(s.centres, s.target, s.selected, s.plane, wide)[200], 1);
}

TEST(TargetUnderside, NothingWithoutAPlaneOrATarget) {
  Scene s = ball_with_probes(kProbes, glm::mat4(1.0f));
  MirrorPlane none;
  const SelectionMask a = target_underside(s.centres, s.target, s.selected, none);
  EXPECT_EQ(count_selected(a), 0u);
  const SelectionMask empty(s.centres.size(), 0);
  EXPECT_EQ(count_selected(target_underside(s.centres, empty, empty, s.plane)), 0u);
}
