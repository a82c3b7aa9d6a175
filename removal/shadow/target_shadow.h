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
// samples (k < min_strength or R^2 < min_r2) has no shadow to remove - unless the caller knows where the light
// is (an intrinsic model's environment, environment_light.h):
//  5. The light near a known one: where steps 2-4 find no shadow, the direction is searched again within a
//     cap around the known light's, by the same R^2, the cones as in step 3, and a shadow that takes away at
//     least min_strength of the light there is accepted whatever its R^2, if the samples it shades are
//     clearly darker than the rest. A light high above the target hides most of its shadow under the target;
//     the crescent that shows is small beside the surface's texture and its baked reflections, so the search
//     over the whole sky prefers a low, wrong light and rejects it (docs/design/deviations.md, The target's
//     cast shadow is removed too).
//  6. The check (others_shadow): the light found must cast the other objects' shadows where the photos are
//     dark too; the caller drops a light that contradicts them.
//  7. Relighting leaves the other objects' shadows where they are (shadow_fraction_beside_others): a point
//     that they shade from the light found is dark from their shadow too, and stays so without the target.
//     Without this, a light fitted to a dark area at another object's foot brightened that object's own
//     shadow (measured against renders without the target on the suite's scenes: the photos the fine-tune
//     trains on moved further from them than the photos as taken).
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
  // Step 5: the cap's angular radius around the known light, and its directions. A 2000-iteration model's
  // environment puts its brightest region 5-30 degrees from the true light; with the cones of step 3 (up to
  // 20 degrees) a 15-degree cap reaches that far, where a 30-degree one let a textured table's low, wrong
  // light win (docs/lab/2026-12-06-shadow-near-the-environments-light.md).
  double known_light_cap_degrees = 15.0;
  int known_light_directions = 160;
  // ... and accepted only where its shadowed samples are darker than the unshadowed ones by this many standard
  // errors of the difference (TargetShadow::contrast): the best of the cap's directions always darkens a few
  // samples of a grainy surface by chance.
  double known_light_min_contrast = 5.0;
  // ... and only over a dielectric: where the support surface's learned F0 (opacity-weighted median near the
  // target) is at most this. A metal shows next to nothing of a cast shadow (its look is the scene's
  // reflection), and what darkens its colour near the target is the target's own reflection baked in, which
  // relighting turns into a bright patch. A dielectric's F0 is 0.02-0.08; a 2000-iteration model learns
  // 0.085-0.09 on the suite's dielectric and marble tables and 0.15-0.35 on its rough metal ones (a mirror-like
  // metal's F0 stays near 0 at that length: it passes, and its colour holds no shadow to find).
  double known_light_max_fresnel = 0.12;
  std::size_t min_samples = 50;  // and of support-plane Gaussians near the target
  // The other objects (others_shadow): Gaussians not in the target that stand above the support surface's
  // plane tolerance with at least this opacity. A short run's fog over a floor is fainter, and counted it
  // would shade every sample.
  double others_opacity = 0.5;
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
  // Signed distance from the support plane, positive on the target's side.
  double height(const glm::dvec3& p) const {
    return glm::dot(plane.normal, up) > 0 ? plane.signed_distance(p) : -plane.signed_distance(p);
  }
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
  bool from_known_light = false;      // found by step 5
  double contrast = 0.0;              // shadowed samples' mean luminance below the others', in standard errors
};

// Fits the light to the samples; known_light (unit, toward the light from the target, or null) enables step 5.
// Throws goris::Error when the samples' arrays differ in size.
TargetShadow fit_target_shadow(const ShadowGeometry& geometry, const ShadowSamples& samples,
                               const TargetOcclusion& occlusion, const ShadowSettings& settings = {},
                               const glm::dvec3* known_light = nullptr);

// Step 6, a check of the light found: the same light casts the other objects' shadows. Over the samples the
// target leaves lit (s < 0.05), `others` (the occlusion by the other objects) predicts where their shadows
// fall; a light is contradicted when at least min_shadowed of those samples' weight lies in the others'
// shadow (> 0.5) and the photos show less than min_strength of a shadow there (k of y = b (1 - k o)). A wrong
// light that lays the target's shadow over a neighbour's real one (a bench's shadow on a lawn) puts the
// neighbour's own shadow on lit ground. Without other objects near the target the check says nothing.
struct OthersShadow {
  double shaded_share = 0.0;  // of the samples' weight the target leaves lit, in the others' shadow
  double strength = 0.0;      // k of the others' shadow in those samples' luminance
  bool contradicts = false;
};
OthersShadow others_shadow(const TargetShadow& shadow, const ShadowSamples& samples, const TargetOcclusion& target,
                           const TargetOcclusion& others, const ShadowSettings& settings = {});

// s in [0, 1] per point: the share of the light's cone the target covers (all 0 when !shadow.found).
std::vector<float> shadow_fraction(const TargetShadow& shadow, const std::vector<glm::vec3>& points,
                                   const TargetOcclusion& occlusion, const ShadowSettings& settings = {});

// The multiplier on a display colour with shadow fraction s that removes the target's shadow.
glm::vec3 shadow_gain(const TargetShadow& shadow, float s, const ShadowSettings& settings = {});

// The target's share s_t of the light at a point that the other objects shade too (s_o, their share of the
// same cone), as the s to relight it with. A point both shade stays in the others' shadow once the target is
// gone: with the shares covering the cone independently the photo shows 1 - k (1 - (1 - s_t)(1 - s_o)) of the
// light and the scene without the target 1 - k s_o, which is 1 / (1 - k s) with s = s_t (1 - s_o) / (1 - k s_o).
// k is the shadow's luminance strength. Equals s_t where nothing else shades the point and 0 where the others
// take the whole light.
float shadow_fraction_beside_others(float target_share, float others_share, double strength);

}  // namespace goris
