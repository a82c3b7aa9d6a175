#pragma once
// The target's cast shadow in a Gaussian scene and its photos (removal/shadow/target_shadow.h has the method):
//
//   const ShadowGeometry geo = shadow_geometry(...);                  // support plane, target's extent
//   TargetOccluder occ(model, target);                                // traces the target's Gaussians alone
//   PlanePixels px = support_plane_pixels(camera, median_depth, alpha, geo);  // per view
//   ... ShadowSamples from px and the photo; fit_target_shadow(geo, samples, occ.function()) ...
//   relight_planar(image, px, shadow_fraction(fit, px.point, occ.function()), fit);  // the shadow is gone
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/io/image.h"
#include "core/scene/gaussians.h"
#include "removal/shadow/environment_light.h"
#include "removal/shadow/target_shadow.h"
#include "render/raster/raster_types.h"
#include "render/trace/gaussian_tracer.h"
#include "train/loop/trainer.h"

namespace goris {

// Rays through the target's Gaussians alone, on the CPU (Embree): nothing else blocks them, because the
// question is what the target took away, not what the rest of the scene did.
class TargetOccluder {
 public:
  TargetOccluder(const GaussianModel& model, const SelectionMask& target);
  TargetOcclusion function() const;

 private:
  GaussianModel target_;
  GaussianTracer tracer_;
};

// The pixels of a view that see the support plane within the geometry's reach: the camera ray's hit on the
// plane, kept where the rendered median depth ([H][W], 0 = none) agrees with it (within 3 % of the depth
// plus twice the plane's tolerance) and alpha ([H][W]) is above 0.5.
struct PlanePixels {
  std::vector<std::uint32_t> pixel;  // y * W + x
  std::vector<glm::vec3> point;      // on the plane, world space
  std::size_t size() const { return pixel.size(); }
};
PlanePixels support_plane_pixels(const Camera& camera, const std::vector<float>& median_depth,
                                 const std::vector<float>& alpha, const ShadowGeometry& geometry);

// Multiplies the listed pixels by shadow_gain(shadow, s[k]): planar [3][H][W] floats, or an HWC Image with
// at least 3 channels. Throws goris::Error when the sizes differ.
void relight_planar(std::vector<float>& image, std::size_t pixels_per_channel, const PlanePixels& px,
                    const std::vector<float>& s, const TargetShadow& shadow);
void relight_image(Image& image, const PlanePixels& px, const std::vector<float>& s, const TargetShadow& shadow);

// Where the fit's samples take their colour. On a glossy support surface the photos' colour there is mostly
// the reflection of the scene, which varies from view to view and hides the shadow from the fit; an intrinsic
// model's own colour is its diffuse term D alone, the same from every view (what it did not put into the traced
// glossy term G, it bakes into D as a fixed colour), and keeps the shadow.
enum class ShadowSampleColour {
  Photos,  // the training photos (a radiance model's colour would carry the reflections too)
  Model,   // the model's rendered colour: D for an intrinsic model
};

// The whole step for `goris remove`: the support plane (shadow_geometry, `fallback` as there), samples on it
// coloured as `sample_colour` says (the model rendered with the target, so pixels it covers are left out; at
// most 20K), the fit, then the views' images (the photos) relit in place. With a shadow found and `out_dir`
// not empty, the share of the light the target took is written per view as grey images (out_dir/VIEW.png).
// `selected` may hold more than `target` (the mirror twin): none of it is a candidate for the support surface.
// `environment` (an intrinsic model's, environment_light.h; may be null): its brightest region above the support
// surface enables the fit's search near that light (target_shadow.h, step 5) where the support's learned F0
// near the target is a dielectric's (ShadowSettings::known_light_max_fresnel); fit.reason then ends with that F0.
// A light whose shadows of the other objects on the support surface the photos do not show is dropped
// (target_shadow.h, step 6): fit.found is then false and fit.reason says so. What the other objects shade
// from the light found is not relit (step 7).
struct ShadowRelight {
  TargetShadow fit;                     // fit.reason says why nothing was found
  std::vector<PlanePixels> pixels;      // per view
  std::vector<std::vector<float>> s;    // per view, per plane pixel (empty when !fit.found)
  std::size_t relit_pixels = 0;         // pixels whose luminance share k s exceeds 5 %
};
ShadowRelight relight_target_shadow(GaussianModel& model, const SelectionMask& target, const SelectionMask& selected,
                                    const MirrorPlane* fallback, std::vector<TrainView>& views,
                                    const RasterSettings& raster, const std::filesystem::path& out_dir,
                                    ShadowSampleColour sample_colour = ShadowSampleColour::Photos,
                                    const EnvironmentImage* environment = nullptr);

}  // namespace goris
