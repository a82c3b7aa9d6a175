#pragma once
// Initial Gaussian scenes: from SfM points (with colours) or from random points in a box, with scales from
// the distances to the nearest neighbours (docs/design/conventions.md, Gaussian parameters and activations).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"

namespace goris {

// Per point: sqrt of the mean squared distance to its k nearest other points (the 3DGS "distCUDA2"
// statistic), via a k-d tree (O(N log N)). Coincident points give 0. Fewer than k+1 points: the
// neighbours there are. A single point gives 0.
std::vector<float> knn_mean_distance(const std::vector<glm::vec3>& points, int k = 3);

// One Gaussian per point: position = point, isotropic log scale = log(knn_mean_distance) (distances
// clamped at sqrt(1e-7) as 3DGS does), identity rotation, opacity init.opacity, SH DC from the colour
// (colour = 0.28209479 * dc + 0.5), higher SH zero, extras from init. sh_degree = 0, max_sh_degree = 3.
GaussianModel init_from_points(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& colors,
                               Device device, const GaussianInit& init = {});

// The point nearest (least squares) to every camera's optical axis, and the cameras' mean distance to it:
// what a capture looks at, and from how far. Parallel axes (one camera): a unit in front of the mean camera.
struct CameraFocus {
  glm::vec3 center{0.0f};
  float mean_distance = 0.0f;
};
CameraFocus camera_focus(const std::vector<Camera>& cameras);

// Axis-aligned box for random initialisation when a data set has no SfM points: centred on the point
// nearest (least squares) to all optical axes, half-size `half_size_ratio` x the mean camera distance
// to it (0.33 puts NeRF-synthetic's cameras at radius 4 around 3DGS's [-1.3, 1.3]^3 box).
struct Box {
  glm::vec3 lo{0.0f}, hi{0.0f};
};
Box box_from_cameras(const std::vector<Camera>& cameras, float half_size_ratio = 0.33f);

// n uniform random points in the box, deterministic for a seed, with 3DGS's synthetic-scene colours: SH DC
// coefficients in [0, 1/255], i.e. mid grey. (Colours drawn in [0, 1/255] themselves, a near-black start,
// scored lower on novel views in both modes: docs/lab/bench/NOTES.md, 2026-11-28, "the random start was
// near-black".)
void random_points(const Box& box, size_t n, std::uint64_t seed, std::vector<glm::vec3>& points,
                   std::vector<glm::vec3>& colors);

}  // namespace goris
