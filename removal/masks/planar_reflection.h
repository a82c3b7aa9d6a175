#pragma once
// The target's reflection in a planar glossy surface, from geometry alone, for any stage-1 model.
//
// A radiance model holds a mirror's reflections as a mirror world behind the surface; an intrinsic model
// should trace them, but after a short stage 1 it often bakes them into its colour too (a metal table's F0
// learned at a small fraction of the truth, the glossy term near black), so deleting the target's Gaussians
// leaves its reflection behind. Either way the photos show the target's reflection where the target,
// mirrored through the surface's plane, covers the visible glossy surface. Rendering the mirrored target
// (its Gaussians reflected through the plane) from each training camera and keeping its coverage inside the
// photo's glossy mask gives that region without tracing and without a crisp mirror twin in the model: the
// removal inpaints it and turns the photo loss off there, so a blurred reflection on a rough surface (where
// the mirror world is no copy of the target) goes as well. The coverage is grown to take in the blur.
// The plane: mirror_twins.h (fitted to an intrinsic model's flat glossy Gaussians) or plane_from_masks.h.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/scene/gaussians.h"
#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"
#include "render/raster/raster_types.h"

namespace goris {

// The Gaussians `selected` of `model` that lie on the target's side of `plane` (centre's signed distance
// > 0), reflected through it: centres mirrored, orientations mirrored (the covariance M S M^T of the mirror
// M, kept a rotation by flipping one local axis), everything else as it was. On the model's device.
// A surface reflects only what stands in front of it. Selected Gaussians behind it are the model's own
// mirror world under the target, or the surface's underside caught by the target's masks (on a
// semi-transparent floor, flat discs up to a third of a metre wide); mirrored, they would land at the
// target's foot and mark a wide patch of the surface as reflection. They go with the removal as they are.
// Throws goris::Error when `selected` does not have one entry per Gaussian.
GaussianModel mirrored_through(const GaussianModel& model, const SelectionMask& selected, const MirrorPlane& plane);

struct ReflectionMaskSettings {
  float alpha_threshold = 0.2f;  // coverage of the mirrored target above which a pixel shows its reflection
  // The region grown by this fraction of the image width (at least 1 px) to take in the reflection's blur.
  // Half and twice as much scored lower on the generalization suite
  // (docs/lab/2026-12-05-where-the-reflections-live.md).
  float grow_fraction = 0.03f;
};

// The pixels of one view where the mirrored target covers the visible glossy surface (glossy_mask > 0.5),
// grown by the settings' margin and kept inside the glossy mask. glossy_mask is [H][W] of `camera`.
Mask planar_reflection_mask(GaussianModel& mirrored, const Camera& camera, const std::vector<float>& glossy_mask,
                            const RasterSettings& raster, const ReflectionMaskSettings& settings = {});

}  // namespace goris
