#pragma once
// The radiance warm-up's mirror world: a radiance model explains a mirror-like surface's reflections by
// virtual geometry behind it, seen through it. Once shading starts the glossy term carries the reflections,
// so those Gaussians only keep the surface translucent and cost time. `intrinsic_prune_mirror_world`
// removes them at the last warm-up iteration (core/train/trainer.cpp).
//
// A Gaussian counts as mirror world when, in the training views with glossy masks, its centre lies behind
// the rendered surface (median depth x (1 + tolerance)) at a glossy pixel in at least `min_views` views and
// is never seen directly: in front of or at the rendered surface, or against the background (alpha <= 0.5).
// Behind a non-glossy surface (occluded) counts neither way.
//
// The rendered surface fails where the warm-up left the glossy surface half transparent: the median depth
// of its pixels then lies in the mirror world, and the mirror world counts as seen (steel_snowman from the
// grey start, 8K iterations: 3-6 of 9.5K Gaussians pruned while about 4K lay under the table top).
// With a plane (`intrinsic_prune_mirror_world_plane`, for planar glossy surfaces: a table top, a floor),
// a centre on the far side of the plane from the cameras counts as behind at every glossy pixel, whatever
// the median depth says; the plane is the one most centres on glossy pixels lie on (RANSAC, as the removal's
// mirror twins, core/removal/mirror_twins.h).
#include <cstdint>
#include <functional>
#include <vector>

#include "core/removal/mirror_twins.h"
#include "core/scene/gaussians.h"
#include "core/train/differentiable_renderer.h"
#include "core/train/trainer.h"

namespace goris {

// Renders a view's median depth and alpha ([H][W] each, host) at the camera's size.
using DepthAlphaRender = std::function<void(const Camera& camera, std::vector<float>& median_depth, std::vector<float>& alpha)>;

// Per Gaussian: 1 = mirror world. plane: null, or a found plane whose far side (from the cameras) is behind
// at glossy pixels.
std::vector<std::uint8_t> find_mirror_world(const GaussianModel& model, const std::vector<TrainView>& views,
                                            const DepthAlphaRender& render, float tolerance, int min_views = 2,
                                            const MirrorPlane* plane = nullptr);

// The plane the centres on glossy pixels lie on: those that fall on a glossy pixel in more than half of the
// glossy views they are in frame of, fitted with fit_mirror_plane. Its normal points to the side most camera
// centres are on. found = false when no plane holds enough of them.
MirrorPlane glossy_surface_plane(const GaussianModel& model, const std::vector<TrainView>& views);

// Finds the mirror world with `renderer`'s median depth and alpha (and with_plane: glossy_surface_plane,
// returned in plane_out when given) and removes it (with its optimiser state); returns how many Gaussians
// went. The caller resets what is sized by the count.
size_t prune_mirror_world(GaussianModel& model, const std::vector<TrainView>& views, DifferentiableRenderer& renderer,
                          float tolerance, bool with_plane = false, MirrorPlane* plane_out = nullptr);

}  // namespace goris
