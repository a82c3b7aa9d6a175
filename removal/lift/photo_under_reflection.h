#pragma once
// Where the fine-tune keeps a view's photo under the target's planar reflection.
//
// The planar reflection mask (removal/masks/planar_reflection.h) takes the photo loss off wherever the
// mirrored target covers the glossy surface, and the hole's 2D fill, smooth from its border, becomes the
// target there. On a textured surface (a marble's veins) the fill wipes the texture that the photos still
// show under a faint reflection, and the fine-tune averages the views' fills into a pale patch. Inside the
// lighting-aware mask the photo has already been dereflected (dereflect.h); where it then differs from the
// view's own fill by no more than the surface's texture differs from its local mean
// (texture_multiple x the surface-detail RMS of surface_detail.h), the difference is the surface's texture,
// not the target, and the photo keeps its loss there. The rest of the reflection - a bright or dark mirror
// image, pixels outside the lighting-aware mask, whose reflection stage 1 did not trace - keeps the fill,
// and so does a margin round the target's silhouette: its contact shadow and the foot of its reflection
// are as dark as a texture's darkest vein. On a plain surface (detail near 0) nothing is kept.
#include <cstddef>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/image.h"

namespace goris {

struct PhotoUnderReflectionSettings {
  // A pixel keeps its photo when the mean over RGB of |photo - fill| is at most this many times the
  // surface's detail RMS (colour units, 0-1).
  double texture_multiple = 2.0;
  // px: pixels this close to the excluded silhouette never keep their photo.
  int silhouette_margin = 3;
};

// `reflection`: the view's planar reflection mask; `lighting`: its lighting-aware mask (the dereflected
// pixels); `silhouette`: what the view leaves out of the photo loss for the target itself (grown
// silhouette U object mask); `photo`: the view's photo as the fine-tune trains on it (planar [3][H][W],
// dereflected); `fill`: the view's 2D fill of its hole (3 interleaved channels); `detail`: the glossy
// surface's detail RMS (< 0: not measured, nothing kept). Returns the part of `reflection` that stays out of
// the photo loss; `kept` (optional) counts the pixels taken out of it. Throws goris::Error when the sizes
// differ.
Mask reflection_left_to_the_fill(const Mask& reflection, const Mask& lighting, const Mask& silhouette,
                                 const std::vector<float>& photo, const Image& fill, double detail,
                                 const PhotoUnderReflectionSettings& settings = {}, std::size_t* kept = nullptr);

}  // namespace goris
