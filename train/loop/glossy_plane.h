#pragma once
// A planar glossy surface (a table top, a polished floor) kept opaque to the mirror world while the shading
// learns. The radiance warm-up explains a mirror's reflections by virtual geometry behind it, seen through
// it (train/loop/mirror_world.h). Pruning it once at the end of the warm-up is not enough: on steel_snowman
// the optimiser moved Gaussians back under the table top after the shading started and rebuilt the mirror
// snowman there (opaque Gaussians just under the table top, tilted 50-81 degrees: docs/lab/bench/NOTES.md,
// 2026-11-29), and the reflected rays then hit the table's own tilted Gaussians.
//
// `intrinsic_glossy_plane` (off by default) finds the glossy surface's plane at the last warm-up iteration
// (from the glossy masks, glossy_surface_plane below), removes the Gaussians beyond it that lie over glossy
// pixels inside its footprint (PlaneFootprint, below), and from then on projects every such centre back onto
// the cameras' side after each update (a projected gradient step).
// Which Gaussians lie over glossy pixels, and the footprint, are refreshed every `kRefreshInterval`
// iterations and whenever the count changes. A Gaussian put back keeps the colour it took on beyond the
// plane; on steel_snowman (8K, with alpha_weight) those painted the snowman's reflection into the table's
// D, which the removal then left behind as a white smear (docs/lab/bench/NOTES.md, 2026-11-29).
// `intrinsic_glossy_plane_prune_sinkers` removes such Gaussians at the next refresh instead. Real
// geometry under the surface that the cameras see directly lies over non-glossy pixels (a table's legs) or
// outside the footprint (its own side) and is left alone. Alone the constraint costs more than it gains: over
// the black background the table stays half transparent. With `alpha_weight` (the images' alpha) it is opaque
// and G carries the reflections (docs/design/deviations.md, The glossy surface held to its plane).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/gaussians.h"
#include "core/scene/mirror_twins.h"

namespace goris {

struct TrainView;  // train/loop/trainer.h; the GlossyPlaneHook (train/loop/hooks/hooks.h) holds the constraint

// Per Gaussian: 1 when its centre falls on a glossy pixel in more than half of the views with glossy masks
// whose frame it is in.
std::vector<std::uint8_t> over_glossy_pixels(const GaussianModel& model, const std::vector<TrainView>& views);

// The glossy surface's plane, its normal towards the cameras: the glossy masks' level plane
// (plane_from_glossy_masks, core/scene/plane_from_masks.h) when the views have masks, moved to the densest
// layer of the centres over glossy pixels near it (the model's own surface, when it has one); else - or when
// the masks give none - the plane the centres over glossy pixels lie on (fit_mirror_plane with the flat
// Gaussians' normals). The warm-up's Gaussians over a mirror-like surface are mostly its mirror world: fitted
// to them, the plane came out tilted 12-30 degrees on the generalization suite's metal tables and 0.4-1.6 above
// its floors; the masks' level plane lies within 0.035 of every table's top
// (docs/lab/2026-12-05-the-glossy-plane-from-the-masks.md). found = false when neither gives one. `source`,
// when given, is told which of the two it came from, for the log.
MirrorPlane glossy_surface_plane(const GaussianModel& model, const std::vector<TrainView>& views,
                                 const std::vector<std::uint8_t>& over_glossy, std::string* source = nullptr);

// Where the surface is, seen along its normal: the cells of a grid in the plane (kCells across the in-band
// centres' extent, or their mean spacing when coarser) that hold a flagged centre within the plane's
// tolerance, closed over kClose cells, with its holes filled, less a margin of kMargin cells along the
// outline. On steel_snowman the table's own side, 0.11 deep, lies beyond the plane over glossy pixels too;
// without the footprint the constraint cut it off (docs/lab/bench/NOTES.md, 2026-11-29).
class PlaneFootprint {
 public:
  static constexpr double kCells = 48;
  static constexpr int kClose = 2, kMargin = 1;
  PlaneFootprint() = default;
  PlaneFootprint(const std::vector<float>& positions, const MirrorPlane& plane, const std::vector<std::uint8_t>& flags);
  bool contains(const glm::dvec3& p) const;  // p projected onto the plane falls inside

 private:
  glm::ivec2 cell_of(const glm::dvec2& in_plane) const;  // -1 or n when off the grid
  std::size_t index(glm::ivec2 c) const { return std::size_t(c.y) * std::size_t(nu_) + std::size_t(c.x); }
  glm::dvec3 u_{1, 0, 0}, v_{0, 1, 0};  // in-plane axes
  glm::dvec2 origin_{0, 0};
  double cell_ = 1;
  int nu_ = 0, nv_ = 0;
  std::vector<std::uint8_t> inside_;  // [nv][nu]; empty = nothing inside
};

class GlossyPlaneConstraint {
 public:
  static constexpr int kRefreshInterval = 100;

  // Fits the plane and prunes beyond it; returns a note for the log. The caller resets what is sized by the
  // count (when pruned() > 0).
  std::string start(GaussianModel& model, const std::vector<TrainView>& views);
  // After an update at iteration `it`: when due (every kRefreshInterval iterations, or when the count
  // changed), with prune_sinkers removes the Gaussians it moved since the last refresh and refreshes the
  // flags; then moves the flagged centres beyond the plane back into the inlier band (at -tolerance / 2).
  // Does nothing without a plane. The caller resets what is sized by the count when pruned > 0.
  struct Step {
    std::size_t moved = 0, pruned = 0;
  };
  Step apply(GaussianModel& model, const std::vector<TrainView>& views, int it, bool prune_sinkers);
  // After apply(): turns the flagged flat Gaussians in the plane's inlier band so that their shortest axis
  // (their rendered normal) is the plane's normal, keeping their shape and in-plane orientation. A mirror's
  // reflected ray is off by twice its normal's error: 1-2 degrees left on steel's table move a reflection by
  // pixels (`intrinsic_glossy_plane_align`; docs/lab/bench/NOTES.md, 2026-11-29 and 2026-12-01). Returns how
  // many were turned.
  std::size_t align_normals(GaussianModel& model) const;

  bool started() const { return started_; }
  const MirrorPlane& plane() const { return plane_; }
  std::size_t pruned() const { return pruned_; }  // at start()
  std::size_t sinkers_pruned() const { return sinkers_pruned_; }  // by apply(), in all

 private:
  bool started_ = false;
  MirrorPlane plane_;
  PlaneFootprint footprint_;  // refreshed with the flags
  std::size_t pruned_ = 0;
  std::size_t sinkers_pruned_ = 0;
  std::vector<std::uint8_t> over_glossy_, sank_;  // per Gaussian; sank_: moved since the last refresh
  int refreshed_at_ = -1;
};

}  // namespace goris
