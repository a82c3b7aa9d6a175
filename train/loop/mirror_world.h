#pragma once
// The radiance warm-up's mirror world: a radiance model explains a mirror-like surface's reflections by
// virtual geometry behind it, seen through it. Once shading starts the glossy term carries the reflections,
// so those Gaussians only keep the surface translucent and cost time. `intrinsic_prune_mirror_world`
// removes them at the last warm-up iteration (MirrorWorldHook, train/loop/hooks/hooks.h).
//
// A Gaussian counts as mirror world when, in the training views with glossy masks, its centre lies behind
// the rendered surface (median depth x (1 + tolerance)) at a glossy pixel in at least `min_views` views and
// is never seen directly: in front of or at the rendered surface, or against the background (alpha <= 0.5).
// Behind a non-glossy surface (occluded) counts neither way.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/scene/gaussians.h"
#include "train/loop/differentiable_renderer.h"
#include "train/loop/trainer.h"

namespace goris {

// Renders a view's median depth and alpha ([H][W] each, host) at the camera's size.
using DepthAlphaRender = std::function<void(const Camera& camera, std::vector<float>& median_depth, std::vector<float>& alpha)>;

// Per Gaussian: 1 = mirror world.
std::vector<std::uint8_t> find_mirror_world(const GaussianModel& model, const std::vector<TrainView>& views,
                                            const DepthAlphaRender& render, float tolerance, int min_views = 2);

// Finds the mirror world with `renderer`'s median depth and alpha and removes it (with its optimiser
// state); returns how many Gaussians went. The caller resets what is sized by the count.
size_t prune_mirror_world(GaussianModel& model, const std::vector<TrainView>& views, DifferentiableRenderer& renderer,
                          float tolerance);

}  // namespace goris
