#pragma once
// Click picking: which Gaussian does a pixel show? The pixel's ray is traced through the Gaussians with the
// tracer's own hit collection and blending (render/trace: Embree over the 1/255 ellipsoid boxes, hits at
// their maximum response t*, blended front to back in (t*, index) order, stopping before T < 1e-4), and the
// Gaussian with the largest blending weight alpha_i T_i along the ray is the answer, with where it was hit.
//
//   GaussianPicker picker(model);               // once per model change (builds the Embree BVH)
//   PickResult p = picker.pick(camera, u, v);   // continuous pixel coordinates (pixel i spans [i, i+1))
//   if (!p.hit) ... "background" ...
//
// A miss is a normal result (hit = false), not an exception: the editor shows it, the CLI turns it into an
// error. Picking runs on the CPU whatever the model's device (the model's arrays are copied once); pick()
// may be called from several threads at once.
#include <cstddef>
#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "core/io/camera.h"

namespace goris {

class GaussianModel;

struct PickSettings {
  // A ray whose largest weight stays below this shows (almost) background: reported as no hit.
  float min_weight = 0.01f;
};

struct PickResult {
  bool hit = false;
  std::uint32_t gaussian = 0;  // index into the model (valid when hit)
  float weight = 0.0f;         // its alpha * T along the ray
  float distance = 0.0f;       // t* of its hit along the unit ray direction (world units from the origin)
  float depth = 0.0f;          // camera-space z of the hit point (pick(camera, ...) only; else = distance)
  glm::vec3 point{0.0f};       // world-space hit point: origin + distance * direction
  float ray_alpha = 0.0f;      // 1 - T after the whole ray (how opaque the pixel is)
  int blended = 0;             // hits blended along the ray
};

class GaussianPicker {
 public:
  explicit GaussianPicker(const GaussianModel& model, const PickSettings& settings = {});
  ~GaussianPicker();
  GaussianPicker(GaussianPicker&&) noexcept;
  GaussianPicker& operator=(GaussianPicker&&) noexcept;

  std::size_t count() const;

  // The ray through continuous pixel coordinates (u, v) of `camera` (pinhole; pass i + 0.5 for the centre
  // of pixel i). Throws goris::Error when (u, v) lies outside the image.
  PickResult pick(const Camera& camera, float u, float v) const;
  // Any ray (direction need not be unit length; distance is along the normalised direction).
  PickResult pick_ray(const glm::vec3& origin, const glm::vec3& direction) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-shot pick of the centre of pixel (x, y) (integers, 0-based, x to the right, y down).
PickResult pick_gaussian(const GaussianModel& model, const Camera& camera, int x, int y, const PickSettings& settings = {});

}  // namespace goris
