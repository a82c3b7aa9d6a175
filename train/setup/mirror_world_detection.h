#pragma once
// A radiance model's mirror world, found from its geometry alone (for `--mode auto`, beside the
// photo-consistency evidence of glossy_detection.h).
//
// A radiance model explains a mirror's reflections by virtual geometry behind the mirror: a copy of what
// stands in front of it, reflected through its plane. That copy is photo-consistent (every view sees it at
// the same virtual place), so the photo-consistency criterion misses a clear near-mirror whose reflections
// the model has already turned into geometry (a dark metal slab with crisp reflections of the balls on it).
// The geometry says it instead: behind a plane that every camera sees from the same side, the surface points
// the views show mirror, through that plane, surface points in front of it. A Lambertian scene has nothing
// behind its ground but a few floaters, and an object's own symmetry planes pass between the cameras.
// (train/loop/mirror_world.h is the other side of it: which Gaussians make a mirror world, once the glossy
// masks are known. This says whether there is one, without masks.)
//
// The search: planes whose normal lies within `cap_degrees` of the direction from the points towards the
// cameras' mean position (a capture looks at a table or floor from above it), offsets at quantiles of the
// points' heights below every camera; for each, the points more than `depth` below the plane are
// reflected through it and count as mirrored when a point in front of the plane lies within `match` of the
// reflection. The same with the plane raised by `null_shift` is the chance level (dense geometry near any
// height matches something). A mirror world is a plane where the mirrored points are a real share of all
// points, most of what lies behind the plane, and well above the chance level. Lengths are fractions of the
// median camera distance.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace goris {

struct MirrorWorldPlaneSettings {
  double cap_degrees = 30.0;     // plane normals searched within this angle of the cameras' side
  int normals = 48;              // in the cap (Fibonacci), then as many within a tenth of it round the best
  int offsets = 32;              // heights tried, at quantiles of the points' heights (5 % to 70 %)
  double depth = 0.05;           // a point is behind the plane from this far below it
  double front = 0.01;           // ... and in front of it from this far above it
  double match = 0.02;           // a reflected point matches a point in front within this distance
  double null_shift = 0.1;       // the chance level: the same plane raised by this much
  double min_share = 0.04;       // mirrored points / all points, at least
  // Mirrored points / points behind the plane, at least: 65-78 % on the suites' mirror-like metal tables,
  // at most 46 % on the other glossy and 35 % on the Lambertian runs (docs/results/auto_mode.md).
  double min_behind_share = 0.6;
  double max_chance = 0.25;      // chance-level matches / mirrored points, at most
  std::size_t max_points = 6000;  // the points are thinned to this many (by a fixed hash of their index)
};

struct MirrorWorldPlane {
  bool found = false;
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit, towards the cameras
  float height = 0.0f;                 // the plane: dot(normal, x) = height
  std::size_t points = 0, behind = 0, mirrored = 0, chance = 0;  // of the best plane
  std::string summary;                 // one line: the numbers and the verdict
};

// points: surface points the views show (world units); cameras: the camera centres. Deterministic.
MirrorWorldPlane find_mirror_world_plane(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& cameras,
                                         const MirrorWorldPlaneSettings& settings = {});

}  // namespace goris
