#pragma once
// The training views the adaptive Gaussian budget holds out of the sampler while densification runs
// (core/train/densify_stop.h), and their PSNR under the trainer's own renderer.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/train/differentiable_renderer.h"
#include "core/train/trainer.h"

namespace goris {

// Every `every`-th view, starting with the first (0, every, 2 every, ...): at least one, never all.
// Throws goris::Error for fewer than two views or every < 2.
std::vector<std::uint32_t> held_out_view_indices(std::size_t n_views, int every);

// An epoch's views before shuffling: 0 .. n_views-1 without `excluded` (sorted ascending).
std::vector<std::uint32_t> epoch_views(std::size_t n_views, const std::vector<std::uint32_t>& excluded);

// Mean PSNR (dB, each view capped at 99) of the renderer's colour of `model` at views[indices] against
// their photos. Forward passes only: the renderer's state of the last training forward is overwritten.
double held_out_psnr(DifferentiableRenderer& renderer, GaussianModel& model, const std::vector<TrainView>& views,
                     const std::vector<std::uint32_t>& indices);

}  // namespace goris
