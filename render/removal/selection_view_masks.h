#pragma once
// Object masks from a 3D selection: per view, the rendered coverage of the selected Gaussians (the
// selection rasterized as an extra channel of the full model, so their alpha * T already accounts for
// everything in front of them: a depth test against the full render), thresholded and cleaned by a small
// morphological close then open. Written as the data sets' object masks are named (mask_XXX.png for
// view r_XXX, else <view name>.png), so `goris select --masks DIR`, the label loss and stage 2 read them.
//
// With the view's photo (a training view), the coverage mask is then refined against the photo:
// GrabCut (OpenCV: colour models of the object and its surroundings, cut along the photo's edges) in a band
// around the coverage mask. The coverage of a short or blurry run is the object's silhouette displaced
// and swollen by a few pixels (large, low-opacity Gaussians, floaters in front of the object that learned
// its colours), while the photo has the exact edge; the band bounds how far the cut may move the mask, so
// it cannot wander onto a similar-coloured object elsewhere in the view.
#include <filesystem>
#include <string>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/io/dataset.h"
#include "core/removal/selection_points.h"
#include "render/raster/rasterizer.h"

namespace goris {

class GaussianModel;

// The full render with the selection as its one extra channel: gbuffer.color is the view,
// gbuffer.extras the selected Gaussians' coverage sum(alpha_i T_i) per pixel. Throws goris::Error when the
// mask size differs from the model's.
RasterOutput render_selection_channel(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                                      const RasterSettings& raster = {});

struct ViewMaskSettings {
  float threshold = 0.5f;  // coverage above which a pixel is the object
  int close_radius = 1;    // pixels: fills pinholes between splats
  int open_radius = 1;     // pixels: drops specks from stray selected Gaussians
  // Photo refinement (used when a photo is given): the band reaches band_fraction of the image's larger
  // side (at least 2 px) on either side of the coverage mask's border; GrabCut runs this many iterations.
  float band_fraction = 0.05f;
  int grabcut_iterations = 5;
  // Sure object for GrabCut: coverage above core_coverage at least core_radius pixels inside the coverage
  // mask (the colour model of the object needs clean samples; a blurry coverage also fills holes such as a
  // torus's, whose border coverage stays below it).
  float core_coverage = 0.9f;
  int core_radius = 3;
};

// The object mask of one view; with `photo` (RGB, CPU, at the camera's size, values in [0, 1]) refined
// against it as described above.
Mask selection_view_mask(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                         const RasterSettings& raster = {}, const ViewMaskSettings& settings = {},
                         const Image* photo = nullptr);

// The photo refinement alone: `coarse` is the coverage mask; pixels farther than the band outside it stay
// background, pixels core_radius deep inside it where the coverage is above core_coverage stay object, and
// GrabCut decides the rest. An empty coarse mask is returned unchanged. Throws goris::Error on a photo of
// another size or not RGB on the CPU.
Mask refine_mask_with_photo(const Mask& coarse, const std::vector<float>& coverage, const Image& photo,
                            const ViewMaskSettings& settings = {});

// The file name a view's object mask has: mask_XXX.png for r_XXX, else <name>.png.
std::string object_mask_file_name(const std::string& view_name);

// Intersection over union of the set pixels (1 when both are empty). Different sizes: goris::Error.
double mask_iou(const Mask& a, const Mask& b);

}  // namespace goris
