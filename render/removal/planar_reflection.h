#pragma once
// The target's reflection in a planar glossy surface, from geometry alone, for any stage-1 model.
//
// A radiance model holds a mirror's reflections as a mirror world behind the surface; an intrinsic model
// traces them. Either way the photos show the target's reflection where the target, mirrored through the
// surface's plane, covers the visible glossy surface. Rendering the mirrored target (its Gaussians
// reflected through the plane) from each training camera and keeping its coverage inside the photo's
// glossy mask gives that region without tracing and without a crisp mirror twin in the model: the removal
// inpaints it and turns the photo loss off there, so a blurred reflection on a rough surface (where the
// mirror world is no copy of the target) goes as well. The coverage is grown to take in the blur.
//
// Which Gaussians are glossy, for fitting the plane on a model without a learned region channel: those
// whose centre falls inside the photos' glossy masks in most views that see it - the surface's own
// Gaussians and a radiance model's mirror world alike (mirror_twins.h fits the plane to the flat ones).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/removal/mirror_twins.h"
#include "core/removal/selection_points.h"
#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"

namespace goris {

// 1 where a centre projects inside the glossy mask (> 0.5) in at least `share` of the views whose image it
// projects into, and into at least `min_views` of them. masks[i] is [H][W] of cameras[i]; an empty mask
// leaves that view out. Throws goris::Error when a mask's size is not its camera's.
std::vector<std::uint8_t> glossy_from_masks(const std::vector<glm::vec3>& centres, const std::vector<Camera>& cameras,
                                            const std::vector<const std::vector<float>*>& masks, float share = 0.5f,
                                            int min_views = 2);

// The Gaussians `selected` of `model` reflected through `plane`: centres mirrored, orientations mirrored
// (the covariance M S M^T of the mirror M, kept a rotation by flipping one local axis), everything else as
// it was. On the model's device.
GaussianModel mirrored_through(const GaussianModel& model, const SelectionMask& selected, const MirrorPlane& plane);

struct ReflectionMaskSettings {
  float alpha_threshold = 0.2f;  // coverage of the mirrored target above which a pixel shows its reflection
  float grow_fraction = 0.03f;   // the region grown by this fraction of the image width (at least 1 px): blur
};

// The pixels of one view where the mirrored target covers the visible glossy surface (glossy_mask > 0.5),
// grown by the settings' margin and kept inside the glossy mask. glossy_mask is [H][W] of `camera`.
Mask planar_reflection_mask(GaussianModel& mirrored, const Camera& camera, const std::vector<float>& glossy_mask,
                            const RasterSettings& raster, const ReflectionMaskSettings& settings = {});

}  // namespace goris
