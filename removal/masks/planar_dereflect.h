#pragma once
// The target's reflection in a planar glossy surface taken out of the photos, from geometry: what the
// surface shows is, to first order, the scene in front of it seen in a mirror, scaled by the surface's
// reflectance and blurred by its roughness. Rendering the Gaussians in front of the plane mirrored through
// it, once with the target and once without, gives the target's share of that mirror image (delta: its
// reflection less what it hid, e.g. another object's reflection behind it). The photo minus
// reflectance * blur(delta) is the photo after the removal - the surface's own texture (a marble's veins)
// and the other objects' reflections kept in place - where a 2D fill paints the region smooth.
//
// Reflectance and blur are not known (a short stage 1 learns a metal's F0 at a fraction of the truth), so
// they are fitted per view on the region itself: the photo's departure from a smooth fill of the region
// (its residual) against delta. Where the fit does not explain the photo (the target's underside, never
// seen but in its reflection, is not what the model guessed), the view keeps the 2D fill
// (planar_dereflect_scene.h says when).
#include <cstddef>
#include <vector>

#include "core/inpaint/mask.h"

namespace goris {

struct PlanarDereflectSettings {
  // Blurs tried for the reflection: Gaussian sigma as a fraction of the image width (a rough surface
  // blurs the mirror image; the planar reflection mask is grown by 3 % of the width for the same reason).
  std::vector<float> blur_fractions{0.0f, 0.006f, 0.012f, 0.024f};
  // Share of the residual's energy the scaled reflection must explain for a view to keep its dereflected
  // photo (on a busy surface, below, any fit with a positive scale does).
  float min_explained = 0.5f;
  float max_reflectance = 1.5f;  // the fitted scale is clamped to [0, this]
  // The plane's offset is searched over +- offset_steps steps of offset_step_ratio times its tolerance:
  // the mirror image moves by twice an error of the plane, and a plane from the masks or the model lies up
  // to a few hundredths off the surface.
  int offset_steps = 4;
  float offset_step_ratio = 0.25f;
  // A busy surface: the smooth fill's own mean squared error on the surface in a band around the region
  // (band_fraction of the image width wide), median over the views, above busy_surface. There the fill
  // loses more (a marble's veins) than a partly fitted reflection leaves. Chosen on the generalization suite
  // (docs/lab/2026-12-06-the-reflection-fitted-out-of-the-photos.md): its marble tables lie at 0.010-0.011,
  // its plain tables at 0.0007-0.0072 (one mirror-like metal table at 0.012: its fits find no reflection).
  float busy_surface = 0.008f;
  float band_fraction = 0.03f;
};

struct PlanarDereflectFit {
  bool applied = false;
  float reflectance = 0.0f;  // the fitted scale of delta
  float blur = 0.0f;         // its sigma in pixels
  float explained = 0.0f;    // 1 - |residual - scale * delta|^2 / |residual|^2 over the region
  std::size_t pixels = 0;    // of the region
};

// Fits scale and blur of `delta` to `photo - smooth` over `region` and, when the fit explains at least
// settings.min_explained of the residual's energy with a positive scale, subtracts scale * blur(delta) from
// `photo` there (clamped to [0, 1]). photo, smooth and delta are planar [3][H][W] with H, W the region's
// size; throws goris::Error on sizes that differ. With no region pixel, or delta zero over the region,
// nothing is applied.
PlanarDereflectFit dereflect_planar_reflection(std::vector<float>& photo, const std::vector<float>& smooth,
                                               const std::vector<float>& delta, const Mask& region,
                                               const PlanarDereflectSettings& settings = {});

// A planar [C][H][W] image blurred per channel with a Gaussian of `sigma` pixels (reflected borders);
// sigma <= 0 returns a copy.
std::vector<float> gaussian_blur_planar(const std::vector<float>& image, int channels, int width, int height,
                                        float sigma);

}  // namespace goris
