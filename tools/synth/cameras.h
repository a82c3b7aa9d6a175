#pragma once
// Camera placement on the upper hemisphere around a look-at point: a Fibonacci (golden-angle) spiral,
// evenly spread in solid angle between two elevations and over an azimuth sector. Test cameras use a
// different phase of the spiral, so they are new viewpoints between the training ones.
#include <vector>

#include "tools/synth/scene_description.h"

namespace goris::synth {

struct CameraRing {
  Vec3 look_at{0, 0, 0};
  double radius = 5.0;
  double min_elevation = 0.35, max_elevation = 1.2;  // radians above the horizon
  double min_azimuth = 0.0, max_azimuth = 6.283185307179586;  // radians, from +X towards +Y
};

// `phase` in [0, 1) shifts the spiral (0 for training views, e.g. 0.5 for test views).
std::vector<CameraView> hemisphere_cameras(const CameraRing& ring, int count, double phase);

}  // namespace goris::synth
