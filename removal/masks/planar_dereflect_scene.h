#pragma once
// The planar dereflection (planar_dereflect.h) over every training view of a removal: the mirror images
// rendered from the stage-1 model, the smooth fill each view's fit compares against, the plane's offset
// that registers the mirror images with the photos, and the rule that decides which views keep their
// dereflected photo as the target of their planar reflection mask (the others keep the 2D fill).
#include <filesystem>
#include <vector>

#include "core/io/image.h"
#include "core/scene/gaussians.h"
#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"
#include "removal/masks/inpaint_mask.h"
#include "removal/masks/planar_dereflect.h"
#include "render/raster/raster_types.h"
#include "train/loop/trainer.h"

namespace goris {

struct PlanarDereflectScene {
  std::size_t views = 0;   // views whose photo was dereflected
  std::size_t pixels = 0;  // their region pixels
  double offset = 0;       // the plane's offset found, less the given one (world units)
  float busyness = 0;      // median over the views of the smooth fill's own error around the region
  bool busy = false;       // busyness > settings.busy_surface: a view keeps any fit with a positive scale
  std::vector<PlanarDereflectFit> fits;  // per view (pixels = 0: no region)
  // Per view where the fit applied (empty elsewhere): the region and the dereflected photo, planar [3][H][W].
  std::vector<Mask> region;
  std::vector<std::vector<float>> rgb;
};

// For every view with a planar reflection mask (`reflection`, one per view, empty = none): the region is the
// mask less the target's own pixels (its Gaussians in front of `plane`, grown 2 px for the soft edge) and
// less what the photo's glossy mask does not call surface; the smooth fill takes the surface alone as its
// source. The mirror images are the Gaussians in front of `plane` (beyond its tolerance) mirrored through it
// and rasterized without background: with the target's (`target`) and without (those not `removed`).
// Nothing in `views` changes. Throws goris::Error on masks or selections that do not match.
PlanarDereflectScene dereflect_planar_views(const GaussianModel& model, const SelectionMask& target,
                                            const SelectionMask& removed, const MirrorPlane& plane,
                                            const std::vector<TrainView>& views, const std::vector<Mask>& reflection,
                                            const RasterSettings& raster, const PlanarDereflectSettings& settings = {});

// Writes, into out_dir (created), every dereflected view's photo as VIEW.png and fits.json: per view with a
// region its fit (scale, blur in pixels, share explained, applied), the plane's offset found and the busyness.
void write_planar_dereflect(const std::filesystem::path& out_dir, const PlanarDereflectScene& scene,
                            const std::vector<TrainView>& views);

// `rgb` (an inpainted colour map of `view`, HWC, 3 or more channels, on the CPU) takes the dereflected photo
// over the view's region where the fit applied; elsewhere it is left as it is. Throws goris::Error when the
// sizes differ.
void paste_planar_dereflect(Image& rgb, const PlanarDereflectScene& scene, std::size_t view);

}  // namespace goris
