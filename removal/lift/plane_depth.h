#pragma once
// The depth the lift places the fill at, where the hole lies on the glossy surface: never in front of the
// surface's plane.
//
// The lift back-projects each reference view's inpainted depth (lift.h), and that depth is the removed
// scene's own, filled in from the hole's border. Where the model's geometry is a fog rather than a surface
// (a rough metal floor learned in 2000 iterations renders its colour from Gaussians 0.6-1.2 above it), the
// fill's new Gaussians land in the air where the target stood, and the views between the reference views
// show them as a floating disc. Where the hole lies on the glossy surface (the removed scene's glossy mask says so) and
// the removal found that surface's plane, nothing of the fill belongs in front of the plane: a depth nearer
// than where the pixel's ray meets the plane (or none) becomes the plane's. A depth beyond it stays: a
// model's surface layer often lies a little below the plane the glossy masks give.
#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/io/image.h"
#include "core/scene/mirror_twins.h"

namespace goris {

// For every pixel of `where`: depth (1 channel, camera z; 0 = none) = max(depth, z_plane), z_plane the
// camera z of the point where the pixel centre's ray meets `plane`. Pixels whose ray is parallel to the
// plane or meets it behind the camera keep their depth. Returns the number of pixels changed. Throws
// goris::Error when the sizes differ from the camera's or the depth has more than one channel.
std::size_t depth_onto_plane(Image& depth, const Camera& camera, const Mask& where, const MirrorPlane& plane);

}  // namespace goris
