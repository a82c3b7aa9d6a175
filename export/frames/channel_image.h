#pragma once
// One channel of a rendered view (render/maps/channels.h) as a viewable image on the host: planar RGB
// [3][H][W] in [0, 1], coloured as the editor's viewports colour it - colour maps as they are, scalar maps in
// grey, depth through TURBO on inverse depth (gbuffer_maps.h), normals as n * 0.5 + 0.5. `goris export
// --video/--renders --channel` writes these. Indirect light is shown as is (the editor's automatic exposure
// would change from frame to frame of a video).
#include <vector>

#include "train/intrinsic/intrinsic_renderer.h"
#include "render/maps/channels.h"
#include "render/raster/rasterizer.h"

namespace goris {

// `gbuffer` is the view's G-buffer (on any device; extras needed for the material channels), `maps` the
// intrinsic renderer's maps of the same view (null for a radiance model). Throws goris::Error naming the
// channel when the inputs do not hold it (an intrinsic channel without maps, the screen-space filter's
// channels without the filter, a material channel without extras) and for the removal's masks, which are
// files of the training views, not renders.
std::vector<float> channel_image(Channel channel, const GBuffer& gbuffer, const IntrinsicMaps* maps);

}  // namespace goris
