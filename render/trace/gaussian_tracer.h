#pragma once
// Differentiable ray tracing through 3D Gaussians (docs/design/maths.md, Tracing Gaussians):
//
//   GaussianTracer tracer(Device::CPU);
//   tracer.build(view, emit);                        // after every change of the Gaussians
//   tracer.trace(rays, out);                         // colour, depth, alpha, extras, hit count per ray
//   ... the loss writes dL/d(outputs) ...
//   tracer.backward(rays, dl_dout, grads, ray_grads);  // grads.* += dL/dparameters; ray grads written
//
// A ray hits a Gaussian at its point of maximum response t* (render/trace/trace_hit.h); hits with
// alpha >= 1/255 and t* > t_min are blended front to back in (t*, index) order, stopping before the hit that
// would bring T (1 - alpha) below 1e-4. Colour is the SH evaluated in the ray direction + 0.5, clamped at 0,
// times the Gaussian's emit weight (only rough-region Gaussians emit into traced rays: pass their weight or
// a 0/1 flag; every Gaussian still occludes). CPU: Embree (or the LBVH), CUDA: an LBVH built on the GPU.
#include <cstddef>
#include <memory>

#include "core/compute/device.h"
#include "core/scene/gaussian_view.h"
#include "render/trace/trace_types.h"

namespace goris {

class GaussianTracer {
 public:
  explicit GaussianTracer(Device device = Device::CPU, const TraceSettings& settings = {});
  ~GaussianTracer();
  GaussianTracer(GaussianTracer&&) noexcept;
  GaussianTracer& operator=(GaussianTracer&&) noexcept;

  // Prepares the Gaussians (pointers on the tracer's device) for tracing: rebuilds the acceleration
  // structure, or refits it when the count is unchanged (settings.refit). `emit` ([N], optional) weights
  // each Gaussian's colour. The arrays must stay alive and unchanged until the last trace/backward call.
  // Throws goris::Error for invalid views (null arrays, SH degree, extras, non-finite parameters on the CPU).
  void build(const GaussianView& gaussians, const float* emit = nullptr);

  // Traces rays (on the tracer's device) into `out`; out.extras gets the view's n_extras channels.
  void trace(const TraceRays& rays, const TraceOutputs& out) const;

  // Back-propagates dL/d(outputs) of the same rays: adds dL/dparameters to `grads` (null arrays skipped;
  // mean2d_grad_norm untouched), writes dL/d(ray origin, direction) to `ray_grads` and adds dL/d(emit) to
  // `grad_emit` when given. Re-traces the rays, so nothing from trace() is needed.
  void backward(const TraceRays& rays, const TraceOutputGrads& grad_out, const GaussianGradView& grads,
                const TraceRayGrads& ray_grads, float* grad_emit = nullptr) const;

  Device device() const;
  const TraceSettings& settings() const;
  int count() const;       // Gaussians of the last build
  bool last_build_refitted() const;  // whether the last build() refitted instead of rebuilding

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace goris
