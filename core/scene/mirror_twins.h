#pragma once
// The target's mirror twin. Over a planar glossy surface (a steel table top, a polished floor) 3DGS learns
// reflections as a mirror world: a copy of each object below the surface, seen through it. The radiance
// warm-up of stage 1 grows it before the shading can explain the reflection by tracing, and it stays.
// Removing the target without its twin leaves the reflection as a ghost: on steel_snowman (4K iterations,
// 128 px) the whole lower snowman stood on the table after removal.
//
// select_mirror_twins() finds the plane the glossy Gaussians lie on (RANSAC, then a least-squares refit of
// the inliers; with normals, only flat Gaussians lying in the plane count), mirrors the target's centres on
// its own side through it, and selects the Gaussians on the far side that lie inside the (slightly grown)
// hull of the mirrored centres. No plane (a curved or scattered glossy set, fewer than min_glossy points)
// selects nothing, and neither does a hull holding fewer than min_twin_share of the target's Gaussians (no
// mirror world there). Known limit: real geometry below the surface inside that hull (a table's leg right
// under the target) goes too. A sight-line test (seen only THROUGH the surface from the training cameras)
// was considered and left out: twins near the surface's edge are seen past the edge from some cameras, so
// the test needs occlusion, not just geometry.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/selection_points.h"

namespace goris {

struct MirrorPlane {
  bool found = false;
  glm::dvec3 normal{0.0, 0.0, 1.0};  // unit; the target's side is n . x > offset
  double offset = 0.0;
  std::size_t inliers = 0, glossy = 0;  // glossy points within `tolerance` of the plane, of all glossy points
  std::size_t candidates = 0;           // the points that could be inliers: all, or those with a normal
  double tolerance = 0.0;               // inlier distance, world units
  double signed_distance(const glm::dvec3& p) const { return glm::dot(normal, p) - offset; }
};

struct MirrorSettings {
  double tolerance_ratio = 0.01;      // inlier distance as a fraction of the glossy set's bounding-box diagonal
  // Of the glossy points (with normals: of those with a normal), for the plane to count as a mirror. Low on
  // purpose: the mirror world is glossy too and can outnumber the surface (steel_snowman at 4K iterations:
  // 21 % of the glossy centres on the table; 8-15 % of all glossy centres but 14-25 % of the flat ones at 8K).
  double min_inlier_fraction = 0.1;
  std::size_t min_glossy = 50;
  int ransac_iterations = 256;
  std::uint64_t seed = 1;
  double hull_growth = 1.15;  // mirrored centres are spread about their centroid by this before the hull
  // A mirror world copies the target: its twin holds a good share of the target's Gaussians (more than half
  // on a mirror-like table). A few Gaussians in the mirrored hull of a dim reflector are the surface's own
  // underside or noise, and removing them made the result worse (docs/lab/bench/NOTES.md, 2026-11-22, "the
  // twin-share rule"), so fewer than this share of the target's Gaussians above the plane selects nothing.
  double min_twin_share = 0.25;
  // With per-point normals (fit_mirror_plane's `normals`): a point is an inlier only when its normal is
  // within this angle of the plane's, and points with a zero normal never are. A glossy surface is made of
  // flat Gaussians lying in it; without this, on steel_snowman from the grey start (where the region channel
  // calls nearly every Gaussian glossy) RANSAC took a tilted plane through the table and the objects' feet.
  double normal_tolerance_deg = 25.0;
  // Optional: RANSAC only counts candidate planes (unit normal n, n . x = offset) this accepts.
  std::function<bool(const glm::dvec3& normal, double offset)> accept;
};

struct MirrorTwins {
  MirrorPlane plane;
  SelectionMask twins;  // per Gaussian, 1 = the target's mirror twin (never a target Gaussian itself)
  std::size_t count = 0;
  std::size_t candidates = 0;  // Gaussians in the mirrored hull; count = 0 when too few of them for a twin
  std::size_t target_above = 0;  // the target's Gaussians above the plane (what the twin would mirror)
};

// The plane most glossy centres lie on; found = false when fewer than min_inlier_fraction of the candidates
// (every centre, or with normals those with a nonzero normal) do. normals: empty, or one per centre
// (flat_normals() in selection_points.h; see MirrorSettings::normal_tolerance_deg).
MirrorPlane fit_mirror_plane(const std::vector<glm::vec3>& glossy_centres, const MirrorSettings& settings = {},
                             const std::vector<glm::vec3>& normals = {});

// The twins below a given plane (found = true; its tolerance sets the margins): the part of
// select_mirror_twins after the fit, for a plane found otherwise (plane_from_masks.h).
MirrorTwins twins_below_plane(const std::vector<glm::vec3>& centres, const SelectionMask& target,
                              const MirrorPlane& plane, const MirrorSettings& settings = {});

// centres: every Gaussian's centre; glossy: 1 where a Gaussian belongs to the glossy region; target: the
// selection; normals: empty or per Gaussian (fit_mirror_plane). Throws goris::Error when the sizes differ.
MirrorTwins select_mirror_twins(const std::vector<glm::vec3>& centres, const std::vector<std::uint8_t>& glossy,
                                const SelectionMask& target, const MirrorSettings& settings = {},
                                const std::vector<glm::vec3>& normals = {});

}  // namespace goris
