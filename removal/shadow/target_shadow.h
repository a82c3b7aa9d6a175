#pragma once
// The target's cast shadow. Removing an object leaves the shadow it cast baked into the colour of the surface
// it stood on: on marble_monkey (4K iterations, 128 px) Suzanne's shadow from the area light was the largest
// error left after removal, in pixels every view saw (so no inpainting mask covers them). The paper handles
// reflections only; this is our addition to the lighting-aware step.
//
// The method works on samples of the support surface (points with their observed colour): the editor and
// `goris remove` take them from the training images, where the shadow is what the camera saw (a Gaussian's
// own colour is not: on marble_monkey two thirds of the table's Gaussians near the target have a black SH
// colour and the table's look comes from their blend).
//  1. Geometry (shadow_geometry): the target's centroid and radius, and the support plane - the plane most
//     non-target centres within radius_ratio x the radius lie on (RANSAC, as for the mirror twin) among
//     those the target rests on. Shadows on other objects are left alone (known limit).
//  2. The light (fit_target_shadow): for each direction d of a Fibonacci sphere, then a cap around the best
//     one, the target's opacity a_i(d) along the ray from sample i toward d (the caller's occlusion
//     function: a tracer over the target's Gaussians alone). The direction whose shadow best explains the
//     samples' darkening wins: a weighted least-squares fit y_i = b + beta a_i of their linear luminance,
//     scored by R^2, beta < 0.
//  3. Its size: a cone of angular radius theta around d (an area light gives soft edges), s_i = mean of
//     a_i over the cone; theta from a short list, again by R^2.
//  4. Its strength, per channel: y_c = b_c (1 - k_c s_i) in linear colour (colour^gamma); k_c is the share
//     of the light the target takes away in full shadow.
// Relighting (shadow_gain) divides linear colour by (1 - k_c s). A scene where no direction darkens enough
// samples (k < min_strength or R^2 < min_r2) has no shadow to remove.
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"

namespace goris {

// Writes alpha[i] in [0, 1]: the opacity the target accumulates along the ray from origins[i] in the unit
// direction directions[i] (0 = the target does not shade it). alpha has the rays' size on entry.
using TargetOcclusion = std::function<void(const std::vector<glm::vec3>& origins,
                                           const std::vector<glm::vec3>& directions, std::vector<float>& alpha)>;

struct ShadowSettings {
  int directions = 256;         // coarse search, a Fibonacci sphere
  int refine_directions = 96;   // then a cap around the coarse best (radius: twice the coarse spacing)
  std::vector<double> cone_degrees{0.0, 2.5, 5.0, 10.0, 15.0, 20.0};  // candidate light sizes (angular radius)
  int cone_samples = 24;
  double radius_ratio = 4.0;    // samples within this x the target's radius of its centroid
  // Support plane: inlier distance / the candidates' bounding-box diagonal, and the share of the candidates
  // that must be inliers. Loose on purpose: learned surfaces are a few Gaussians thick (marble_monkey at 2K
  // iterations: 11 % of the candidates within 1 %, 21 % within 2 %).
  double plane_tolerance_ratio = 0.02;
  double min_plane_fraction = 0.1;
  double gamma = 2.2;           // display colour -> linear radiance (shadows scale radiance)
  double min_strength = 0.15;   // luminance k below this: no shadow
  // R^2 of the luminance fit below this: no shadow. A true shadow fits clearly above it and the wrong lights
  // fitted to reflections or noise clearly below, and relighting by a wrong light costs quality
  // (docs/lab/bench/NOTES.md, 2026-11-21, "the target's cast shadow").
  double min_r2 = 0.15;
  double min_shadowed = 0.02;   // share of the samples' weight with a_i > 0.5 for a direction to be scored
  // k is capped here, so a linear gain never exceeds 1 / (1 - max_strength) (33x; 4.9x in display values). A
  // shadow cast by the suite's area lights measures 0.9 and more where the fit is clear (R^2 > 0.3): a lower cap
  // leaves it half-dark, a cap nearer 1 amplifies the noise of fully shadowed pixels without bound.
  double max_strength = 0.97;
  std::size_t min_samples = 50;  // and of support-plane Gaussians near the target
};

struct ShadowGeometry {
  bool found = false;
  std::string reason;        // why there is no support plane
  MirrorPlane plane;         // the support plane; `up` points to the target's side
  glm::dvec3 up{0.0, 0.0, 1.0};
  glm::dvec3 centroid{0.0};  // of the target's centres
  double radius = 0.0;       // 90th percentile of their distances to the centroid
  double reach = 0.0;        // samples within this distance of the centroid (radius_ratio x radius)
  bool near_plane(const glm::dvec3& p) const { return std::abs(plane.signed_distance(p)) <= plane.tolerance; }
  bool in_reach(const glm::dvec3& p) const { return glm::length(p - centroid) <= reach; }
};

// centres / weights (opacity): every Gaussian's; target: the selection; candidates: the Gaussians that may
// make up the support surface. `fallback` (e.g. the glossy surface's plane of the mirror-twin step) serves
// when no plane is found near the target and it passes within reach of the target's centroid: over a
// mirror the learned mirror world crowds the surface out of the neighbourhood (steel_snowman). Throws
// goris::Error when the sizes differ or the target is empty.
ShadowGeometry shadow_geometry(const std::vector<glm::vec3>& centres, const std::vector<float>& weights,
                               const SelectionMask& target, const SelectionMask& candidates,
                               const ShadowSettings& settings = {}, const MirrorPlane* fallback = nullptr);

// Points on the support surface with the colour seen there (display values, e.g. a pixel of a photo).
struct ShadowSamples {
  std::vector<glm::vec3> position, colour;
  std::vector<float> weight;
  std::size_t size() const { return position.size(); }
  void add(const glm::vec3& p, const glm::vec3& c, float w = 1.0f) {
    position.push_back(p), colour.push_back(c), weight.push_back(w);
  }
};

struct TargetShadow {
  bool found = false;
  std::string reason;                 // why nothing was found, or a one-line summary when found
  glm::dvec3 light_direction{0.0, 0.0, 1.0};  // unit, from the surface toward the light
  double cone_degrees = 0.0;
  glm::dvec3 strength{0.0};           // k per channel (linear RGB)
  double strength_luminance = 0.0;
  double r2 = 0.0;                    // of the luminance fit
  std::size_t samples = 0;            // used in the fit
};

// Fits the light to the samples. Throws goris::Error when the samples' arrays differ in size.
TargetShadow fit_target_shadow(const ShadowGeometry& geometry, const ShadowSamples& samples,
                               const TargetOcclusion& occlusion, const ShadowSettings& settings = {});

// s in [0, 1] per point: the share of the light's cone the target covers (all 0 when !shadow.found).
std::vector<float> shadow_fraction(const TargetShadow& shadow, const std::vector<glm::vec3>& points,
                                   const TargetOcclusion& occlusion, const ShadowSettings& settings = {});

// The multiplier on a display colour with shadow fraction s that removes the target's shadow.
glm::vec3 shadow_gain(const TargetShadow& shadow, float s, const ShadowSettings& settings = {});

}  // namespace goris
