#pragma once
// The glossy surface's plane from the photos' glossy masks alone: the plane through which the masks of
// different views map onto each other.
//
// A table top or a floor seen from several cameras is one planar region; the plane induces a homography
// between any two views, and only the true plane maps one view's glossy mask onto the other's. So for a
// level plane (normal: the cameras' mean up direction, as photos are taken upright and tables and floors
// are level) each candidate height is scored by the mean IoU between every sampled view's mask and its
// nearest neighbours' masks carried over by the plane; the best height is refined by a finer search and the
// normal by a small search of tilts around the level one.
// Objects standing on the surface hide parts of it in some views, which lowers every candidate's score
// alike. No model is needed: a radiance model of a mirror-like surface has no Gaussians on the surface
// (it shows a mirror world behind it), which is why fitting the plane to Gaussians fails there.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/io/camera.h"
#include "core/scene/mirror_twins.h"

namespace goris {

struct PlaneFromMasksSettings {
  int views = 12;         // views sampled (evenly) as the reference of a comparison
  int neighbours = 2;     // each compared with its nearest views by camera direction
  int step = 2;           // pixels: the comparison's sampling grid
  int coarse = 96;        // candidate heights of the first search; the second refines around the best
  float min_iou = 0.5f;   // the best plane's mean IoU must reach this, else found = false
  float min_share = 0.002f;  // masks covering less of their image are left out (a view missing the surface)
  float max_tilt_deg = 6.0f;  // the normal is searched this far from the cameras' mean up...
  int tilt_steps = 3;         // ...on a (2 tilt_steps + 1)^2 grid of tilts
  float tie_iou = 0.002f;     // scores this close are a tie (see PlaneHeights)
};

// The plane (normal within max_tilt_deg of the cameras' mean up, towards them) and its mean IoU. masks[i]
// is [H][W] of cameras[i] in [0, 1] (> 0.5 = glossy), empty where a view has none. found = false with fewer
// than two usable views, or when no height reaches min_iou. tolerance is 1 % of the cameras' spread.
struct PlaneFromMasks {
  MirrorPlane plane;
  double iou = 0;
};
// Where to search, as heights up . x (up = mean_camera_up). A surface that fills every view (a floor reaching
// past the images' edges) maps onto itself at nearly any height, so the removal narrows the search to where
// the target rests and prefers that height on near-ties (removal/pipeline/removal_pipeline.cpp). Absent: from
// twice the cameras' spread below the lowest camera up to it, and the best score wins.
struct PlaneHeights {
  double low = 0, high = 0;
  std::optional<double> preferred;
};
PlaneFromMasks plane_from_glossy_masks(const std::vector<Camera>& cameras,
                                       const std::vector<const std::vector<float>*>& masks,
                                       const PlaneFromMasksSettings& settings = {},
                                       std::optional<PlaneHeights> heights = std::nullopt);

// Where the target rests, as the search band for plane_from_glossy_masks: from the bottom of the target's own
// Gaussians (5th percentile along up of the centres where target[i] is set) down to half the target's height,
// preferring the bottom. Over a glossy surface a radiance model selects the target's reflection with it (a
// mirror world below the surface, inside the target's masks in many views). Those Gaussians are seen on
// glossy pixels, through the surface, while the target's own are seen on non-glossy ones (a glossy mask
// leaves out what stands in front of the surface), so a Gaussian counts only when it falls on a glossy pixel
// in at most half the views whose image it falls in. nullopt with fewer than 10 Gaussians counted.
std::optional<PlaneHeights> target_rest_heights(const std::vector<Camera>& cameras,
                                                const std::vector<const std::vector<float>*>& masks,
                                                const std::vector<glm::vec3>& centres,
                                                const std::vector<std::uint8_t>& target);

// The cameras' mean up direction (minus the image's down axis in world space), unit; zero if they cancel.
glm::dvec3 mean_camera_up(const std::vector<Camera>& cameras);

}  // namespace goris
