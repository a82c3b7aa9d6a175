#pragma once
// Fine-tune targets inside the lighting-aware mask (our change to the paper; `goris remove
// --lighting-targets exclude` restores the paper's rule).
//
// The paper switches the photo loss off where the target shows up in reflections, so that the photos do
// not teach the removed scene the target's reflection again. Those pixels then learn nothing: they drift
// with the neighbouring Gaussians that other pixels train. Measured on steel_snowman
// (docs/lab/bench/NOTES.md, 2026-11-22), supervising them with the unchanged photos (`--ablate lamask`) even
// scored a little higher than leaving them out. Here they keep a target: the photo minus what stage 1 itself
// says the target added there,
//
//     photo' = photo - (C_with_target - C_removed)  =  C_removed + (photo - C_with_target),
//
// i.e. the removed scene's shaded render plus stage 1's own residual. Where the glossy term explains the
// reflection (traced rays that hit the target, the environment light the target hid), it is taken out;
// where stage 1 did not explain it, the photo is kept as it is.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/scene/gaussians.h"
#include "train/loop/trainer.h"

namespace goris {

class IntrinsicRenderer;

// photo -= with_target - removed on the pixels of `where`, clamped to [0, 1]. All images planar [3][H][W]
// at the mask's size. Returns the sum over those pixels of the mean-RGB |change|. Throws goris::Error when
// the sizes differ.
double subtract_reflection(std::vector<float>& photo, const std::vector<float>& with_target,
                           const std::vector<float>& removed, const Mask& where);

struct DereflectResult {
  std::size_t views = 0, pixels = 0;  // views with a non-empty mask; pixels changed (summed over views)
  double mean_change = 0;             // mean-RGB |change| per pixel, averaged over those pixels
};

// The whole step for `goris remove`: for every view whose lighting-aware mask is not empty, renders the
// stage-1 model with and without the target (shading on) and dereflects the view's photo inside the mask.
// With `out_dir` not empty the changed photos are written there (VIEW.png). `tell(i, n)` reports progress,
// `cancelled()` stops between views (the photos done so far stay changed).
DereflectResult dereflect_views(IntrinsicRenderer& renderer, GaussianModel& with_target,
                                GaussianModel& removed, const std::vector<Mask>& lighting,
                                std::vector<TrainView>& views, const std::filesystem::path& out_dir,
                                const std::function<void(std::size_t, std::size_t)>& tell = {},
                                const std::function<bool()>& cancelled = {});

}  // namespace goris
