#pragma once
// Stage 1 in intrinsic mode behind the trainer's DifferentiableRenderer interface (docs/design/maths.md,
// paper Sec. 3.2 and S1.1-S1.5). One forward pass:
//
//   G-buffer (rasterize with the material extras)
//   -> reflection rays of the glossy pixels (make_reflection_rays)
//   -> trace them through the Gaussians, rough ones emitting (GaussianTracer, emit = region weight m)
//   -> L_ind, V (traced_to_images) -> screen-space filter at R_s = Net(roughness, traced depth, 1 / depth)
//      (with coarse tracing, coarse_tracing.h: one ray per block of pixels the filter blurs anyway, traced
//      in two passes around the net, and a weighted pyramid that ignores the untraced pixels)
//   -> C = D + (1 - M) F (L_ind' + L_dir' V')  (shade; L_dir' from the environment map)
//
// and the backward pass walks it in reverse into the Gaussians (through the G-buffer and the traced hits),
// the environment map and the roughness net. Until the warm-up ends (config.intrinsic.warmup, scaled to the
// run's length) forward() returns the plain rasterized colour (radiance only); the material channels are
// still rendered so that the label and region losses train from the start.
//
// The depth inputs of the roughness net are treated as constants (the net steers the blur level; its
// gradient to roughness is kept). The per-pixel glue between stages (emit weights, the net's input image)
// runs on the host; on CUDA that costs a few small transfers per iteration.
#include <cstdint>
#include <memory>
#include <string>

#include "render/envmap/environment_map.h"
#include "render/raster/rasterizer.h"
#include "render/shading/deferred_shading.h"
#include "render/ssf/glossy_filter.h"
#include "render/ssf/roughness_net.h"
#include "render/trace/gaussian_tracer.h"
#include "train/config/train_config.h"
#include "train/loop/differentiable_renderer.h"
#include "train/loop/emit_weights.h"
#include "train/optimizer/flat_adam.h"

namespace goris {

// Host images of one intrinsic render, planar, for maps and the editor (empty when not computed).
struct IntrinsicMaps {
  int width = 0, height = 0;
  std::vector<float> color;       // final C [3][H][W]
  std::vector<float> sh_color;    // D (SH radiance) [3][H][W]
  std::vector<float> glossy;      // G [3][H][W] (before the (1 - M) weight)
  std::vector<float> indirect;    // L_ind' [3][H][W] (filtered when the filter is on)
  std::vector<float> visibility;  // V' [H][W]
  std::vector<float> env;         // L_dir' [3][H][W]
  std::vector<float> screen_roughness;  // R_s [H][W] (empty without the filter)
  // The traced L_ind [3][H][W] and V [H][W] before the screen-space filter (empty without the filter, where
  // indirect and visibility are these): what the reflection rays brought back, before R_s blurs it. With
  // coarse tracing, the pixels whose block shares one ray are 0 here.
  std::vector<float> indirect_traced, visibility_traced;
  std::size_t rays = 0;           // traced rays
  std::size_t glossy_pixels = 0;  // pixels with a reflection ray (= rays unless coarse tracing saved some)
};

// Wall time of each stage of the last forward / backward (ms), when profiling is on (CUDA is synchronised
// around each stage, which costs a little).
struct IntrinsicTimes {
  double raster = 0, rays = 0, trace = 0, filter = 0, shade = 0;                        // forward
  double shade_back = 0, filter_back = 0, trace_back = 0, raster_back = 0;              // backward
  std::size_t rays_traced = 0;  // reflection rays traced in the forward pass ...
  std::size_t rays_glossy = 0;  // ... of this many glossy pixels (the difference: saved by coarse tracing)
  std::size_t net_pixels = 0;   // the roughness net ran on this many pixels (its window) ...
  std::size_t pixels = 0;       // ... of the image's
  double forward_total() const { return raster + rays + trace + filter + shade; }
  double backward_total() const { return shade_back + filter_back + trace_back + raster_back; }
};

// Reflection rays of every shaded frame since the renderer was made (or reset_ray_totals()).
struct IntrinsicRayTotals {
  std::uint64_t frames = 0, glossy = 0, traced = 0;
  double saved_fraction() const { return glossy ? 1.0 - double(traced) / double(glossy) : 0.0; }
};

class IntrinsicRenderer final : public DifferentiableRenderer {
 public:
  // `extent`: the scene extent (ray offset default); the config's intrinsic settings, iterations and
  // background define everything else.
  IntrinsicRenderer(const TrainConfig& config, float extent, Device device);
  ~IntrinsicRenderer() override;

  Device device() const override { return device_; }
  bool wants_extras() const override { return true; }
  void begin_iteration(int iteration) override;
  RenderedImages forward(const GaussianView& gaussians, const Camera& camera) override;
  void backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) override;
  double depth_distortion(const GaussianView& gaussians, const Camera& camera, const DistortionDepthRange& range,
                          float weight, const float* pixel_weight, const GaussianGradView& grads) override;
  void step_own_parameters(int iteration) override;
  std::string save_own_state() const override;
  void load_own_state(const std::string& bytes, const std::string& source) override;

  // Shading on or off regardless of the iteration (rendering a trained run: on).
  void set_shading(bool on) { shading_ = on; }
  void set_emit_weights(std::vector<float> weights, bool or_region) override {
    emit_override_ = std::move(weights);
    emit_override_on_device_ = {};
    emit_or_region_ = or_region;
  }
  // The same rule for whatever model is rendered next (intrinsic_emit = mask | max on a trained run): the
  // weights are recomputed from the centres and these masks in a forward pass whose centres differ from the
  // last ones, so they follow edits and removals (a per-Gaussian array kept from training would not).
  // Empty = off.
  void set_emit_masks(std::vector<GlossyMaskView> views, bool or_region) {
    emit_masks_ = std::move(views);
    emit_or_region_ = or_region;
    emit_positions_.clear();
  }
  bool shading() const { return shading_; }
  int shading_from() const { return shading_from_; }

  // Renders with shading on and returns every intermediate as host images (the G-buffer itself is last()).
  IntrinsicMaps render_maps(const GaussianView& gaussians, const Camera& camera);
  const RasterOutput& last() const { return raster_; }

  // E_obj of the lighting-aware mask (paper Sec. 3.3) as a host image [H][W]: the reflection rays of the
  // glossy pixels carry the object label (sum of w * label along the ray) instead of colour, the result is
  // filtered like L_ind (same pyramid, same screen roughness) and weighted like the glossy term in the
  // final colour, by (1 - M) F (F: Schlick, mean over RGB). With fresnel_reference != 1 the weight is
  // min(1, F / fresnel_reference) (removal_pipeline: the scene's own F0 scale, see lighting_aware_mask.h).
  // Needs the label channel in the Gaussians' extras.
  std::vector<float> reflected_label(const GaussianView& gaussians, const Camera& camera, float fresnel_reference = 1.0f);

  void set_profile(bool on) { profile_ = on; }
  const IntrinsicTimes& times() const { return times_; }  // stage times (when profiling) and ray counts
  const IntrinsicRayTotals& ray_totals() const { return ray_totals_; }
  void reset_ray_totals() { ray_totals_ = {}; }

  EnvironmentMap& environment() { return env_; }
  ssf::RoughnessNet<float>& net() { return net_; }

 private:
  struct Frame;
  void shade_forward(const GaussianView& gaussians, const Camera& camera, bool maps);
  void trace_rays(const ReflectionRays& rays, std::size_t first, std::size_t count, Buffer<float>& color,
                  Buffer<float>& depth, Buffer<float>& alpha, std::size_t at);
  // R_s from the net; whole_image: on every pixel (the maps show it), else on the window the shading reads
  // (pixel_window.h: the same values there, computed on the surface pixels' bounding box only).
  void net_forward(Frame& f, const Buffer<float>& distance, bool whole_image);
  // The Gaussians as the reflection rays see them: with intrinsic_trace_glossy_transparent, those whose emit
  // weight (f.emit) is below it get a zero opacity (f.trace_logits, which must outlive the tracer's use).
  GaussianView traced_view(const GaussianView& gaussians, Frame& f) const;

  TrainConfig config_;
  float extent_;
  Device device_;
  RasterSettings raster_settings_;
  ShadingSettings shading_settings_;
  TracedImageSettings traced_settings_;
  int shading_from_ = 0;
  bool shading_ = false;
  std::vector<float> emit_override_;  // set_emit_weights(); empty = the region weight M
  Buffer<float> emit_override_on_device_;  // its copy on the renderer's device, uploaded when first needed
  bool emit_or_region_ = false;       // emit = max(M, override) instead of the override
  std::vector<GlossyMaskView> emit_masks_;  // set_emit_masks(): recompute emit_override_ per forward pass ...
  std::vector<float> emit_positions_;       // ... when the centres differ from these
  std::uint32_t frame_seed_ = 0;  // coarse tracing: which pixel of a block is traced (the iteration)

  EnvironmentMap env_;
  FlatAdam env_adam_;
  ssf::RoughnessNet<float> net_;
  FlatAdam net_adam_;
  ssf::GlossyFilter<float> filter_;
  GaussianTracer tracer_;

  bool profile_ = false;
  IntrinsicTimes times_;
  IntrinsicRayTotals ray_totals_;
  RasterOutput raster_;
  std::unique_ptr<Frame> frame_;  // the shading pass's intermediates, kept for backward()
};

}  // namespace goris
