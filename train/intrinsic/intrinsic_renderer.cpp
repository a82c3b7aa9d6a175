#include "train/intrinsic/intrinsic_renderer.h"

#include "core/compute/primitives.h"
#include "train/intrinsic/intrinsic_glue.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include "core/compute/memory.h"
#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "train/intrinsic/coarse_tracing.h"
#include "train/intrinsic/own_state_io.h"
#include "train/optimizer/lr_schedule.h"
#include "train/radiance/depth_distortion_pass.h"
#include "train/radiance/raster_renderer.h"

namespace goris {

namespace {

constexpr MaterialChannels kChannels{extra::kRegion, extra::kFresnel, extra::kRoughness};

// A gradient plane set from the trainer's (possibly null) image gradients.
Buffer<float> grad_plane(const float* given, std::size_t n, Device d) {
  Buffer<float> b(n, d);
  if (given)
    device_copy(b.data(), d, given, d, n * sizeof(float));
  else
    b.fill_zero();
  return b;
}

// Adds the wall time of its scope to `slot` when profiling (synchronising the device first and last).
class StageTimer {
 public:
  StageTimer(bool on, Device d, double& slot) : on_(on), d_(d), slot_(slot) {
    if (!on_) return;
    device_synchronize(d_);
    t0_ = std::chrono::steady_clock::now();
  }
  ~StageTimer() {
    if (!on_) return;
    device_synchronize(d_);
    slot_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  bool on_;
  Device d_;
  double& slot_;
  std::chrono::steady_clock::time_point t0_;
};

// An uninitialised ray list of n rays on device d.
ReflectionRays ray_list(std::size_t n, Device d) {
  ReflectionRays r;
  r.pixels = Buffer<std::uint32_t>(n, d);
  r.origins = Buffer<float>(3 * n, d);
  r.directions = Buffer<float>(3 * n, d);
  r.count = n;
  return r;
}

}  // namespace

// What the shading pass keeps for backward().
struct IntrinsicRenderer::Frame {
  Camera camera;
  SurfaceImages surface;
  ReflectionRays rays;                          // the traced rays (coarse tracing: first pass, then the rest)
  Buffer<float> emit;                           // [N] region weight of each Gaussian (rough ones emit)
  Buffer<std::uint8_t> region_emits;            // [N] 1 where emit is M (else set_emit_weights(): no gradient to M)
  Buffer<float> trace_logits;                   // [N] opacity logits the rays see (trace_glossy_transparent), or empty
  Buffer<float> ray_color, ray_depth, ray_alpha;  // per ray
  Buffer<float> L_raw, V_raw;                   // traced_to_images
  Buffer<float> L, V;                           // what shade() read (filtered or raw)
  Buffer<float> filtered;                       // [4][H][W] filter output
  Buffer<float> rs;                             // [H][W] screen roughness
  Buffer<float> mass;                           // [H][W] filter mass (coarse tracing left rays out), or empty
  std::size_t glossy = 0;                       // glossy pixels (rays.count of them were traced)
  bool use_filter = false;
  const Buffer<float>* mass_or_null() const { return mass.empty() ? nullptr : &mass; }
  ShadeOutputs shaded;
};

IntrinsicRenderer::IntrinsicRenderer(const TrainConfig& config, float extent, Device device)
    : config_(config),
      extent_(extent),
      device_(device),
      raster_settings_(RasterRenderer::settings_for(config)),
      env_(config.intrinsic.env_resolution, device, config.intrinsic.env_initial),
      env_adam_(env_.param_count(), device),
      net_(ssf::NetConfig{3, 8, config.intrinsic.net_hidden_layers}, device,
           config.seed * 7919 + 17),
      net_adam_(net_.param_count(), device),
      tracer_(device) {
  if (!(extent > 0)) throw Error("intrinsic renderer", "the scene extent must be positive");
  shading_settings_.ray_offset =
      config.intrinsic.ray_offset > 0 ? config.intrinsic.ray_offset : ShadingSettings::default_ray_offset(extent);
  for (int c = 0; c < 3; ++c) shading_settings_.env_center[c] = config.intrinsic.env_center[c];
  shading_settings_.env_radius = config.intrinsic.env_radius;
  traced_settings_.divide_opaque = config.intrinsic.divide_opaque;
  shading_from_ = config.shading_from();
  env_.update();
}

IntrinsicRenderer::~IntrinsicRenderer() = default;

void IntrinsicRenderer::begin_iteration(int iteration) {
  shading_ = iteration > shading_from_;
  frame_seed_ = std::uint32_t(iteration);  // coarse tracing's representatives move from one iteration to the next
}

RenderedImages IntrinsicRenderer::forward(const GaussianView& gaussians, const Camera& camera) {
  if (gaussians.n_extras != extra::kCount)
    throw Error("intrinsic renderer", "the Gaussians carry " + std::to_string(gaussians.n_extras) +
                                          " extra channels, shading needs the " + std::to_string(extra::kCount) +
                                          " material channels");
  times_ = IntrinsicTimes{};
  {
    StageTimer t(profile_, device_, times_.raster);
    raster_ = rasterize(gaussians, camera, raster_settings_, device_);
  }
  frame_.reset();
  RenderedImages r = rendered_from_raster(raster_);
  if (shading_) {
    shade_forward(gaussians, camera, false);
    r.color = frame_->shaded.color.data();
  }
  return r;
}

double IntrinsicRenderer::depth_distortion(const GaussianView& gaussians, const Camera& camera,
                                           const DistortionDepthRange& range, float weight, const float* pixel_weight,
                                           const GaussianGradView& grads) {
  return depth_distortion_pass(gaussians, camera, raster_settings_, range, weight, pixel_weight, grads, device_);
}

void IntrinsicRenderer::trace_rays(const ReflectionRays& rays, std::size_t first, std::size_t count,
                                   Buffer<float>& color, Buffer<float>& depth, Buffer<float>& alpha, std::size_t at) {
  if (count == 0) return;
  TraceOutputs out;
  out.color = color.data() + 3 * at;
  out.depth = depth.data() + at;
  out.alpha = alpha.data() + at;
  tracer_.trace({rays.origins.data() + 3 * first, rays.directions.data() + 3 * first, count}, out);
}

void IntrinsicRenderer::net_forward(Frame& f, const Buffer<float>& distance, bool whole_image) {
  // The net's input: (roughness, traced hit distance, 1 / view depth), distances in scene extents.
  const GBuffer& g = raster_.gbuffer;
  const std::size_t hw = g.pixels();
  Buffer<float> in(3 * hw, device_);
  intrinsic_glue::net_input(device_, g.extras.data() + std::size_t(extra::kRoughness) * hw, distance.data(),
                            g.depth.data(), g.alpha.data(), hw, extent_, in.data());
  // Shading, its backward, the coarse tracing's ray selection and the lighting-aware label read R_s only on
  // surface pixels (alpha > min_alpha).
  ssf::PixelWindow window{0, 0, g.width, g.height};
  if (!whole_image) {
    const std::vector<float> host_alpha = device_ == Device::CPU ? std::vector<float>{} : g.alpha.to_host();
    const float* alpha = device_ == Device::CPU ? g.alpha.data() : host_alpha.data();
    window = ssf::net_window(alpha, g.width, g.height, shading_settings_.min_alpha, net_.receptive_radius());
    if (window.empty()) window = {0, 0, g.width, g.height};  // no surface pixel: nothing reads R_s
  }
  times_.net_pixels = std::size_t(window.width()) * std::size_t(window.height());
  times_.pixels = hw;
  net_.forward(in, g.height, g.width, f.rs, &window);
}

GaussianView IntrinsicRenderer::traced_view(const GaussianView& gaussians, Frame& f) const {
  const float threshold = config_.intrinsic.trace_glossy_transparent;
  if (!(threshold > 0)) return gaussians;
  const std::size_t n = std::size_t(gaussians.count);
  if (f.trace_logits.size() != n) {
    f.trace_logits = Buffer<float>(n, device_);
    intrinsic_glue::transparent_logits(device_, gaussians.opacity_logits, f.emit.data(), n, threshold,
                                       f.trace_logits.data());
  }
  GaussianView v = gaussians;
  v.opacity_logits = f.trace_logits.data();
  return v;
}

void IntrinsicRenderer::shade_forward(const GaussianView& gaussians, const Camera& camera, bool maps) {
  auto f = std::make_unique<Frame>();
  const GBuffer& g = raster_.gbuffer;
  const int W = g.width, H = g.height;
  const std::size_t hw = g.pixels();
  f->camera = camera;
  f->surface = surface_from_gbuffer(g, kChannels);
  f->use_filter = config_.intrinsic.screen_space_filter;
  ReflectionRays glossy;
  {
    StageTimer t(profile_, device_, times_.rays);
    glossy = make_reflection_rays(camera, f->surface, shading_settings_, device_);
  }
  const std::size_t n_glossy = glossy.count;
  f->glossy = n_glossy;
  const bool coarse = f->use_filter && config_.intrinsic.coarse_tracing && n_glossy > 0;
  const CoarseTracingSettings cs{std::min(config_.intrinsic.coarse_max_level, filter_.levels() - 2), filter_.levels(),
                                 frame_seed_};

  // Trace: every Gaussian occludes, rough ones (region weight m) emit. No extras needed on the rays.
  {
    StageTimer t(profile_, device_, times_.trace);
    const std::size_t n = std::size_t(gaussians.count);
    if (!emit_masks_.empty()) {  // recomputed only when the centres changed (the editor redraws one model)
      std::vector<float> pos = download(gaussians.positions, 3 * n, device_);
      if (pos != emit_positions_) {
        emit_override_ = glossy_mask_emit_weights(pos, emit_masks_);
        emit_override_on_device_ = {};
        emit_positions_ = std::move(pos);
      }
    }
    const bool overridden = emit_override_.size() == n;
    if (overridden && emit_override_on_device_.size() != n)
      emit_override_on_device_ = Buffer<float>(emit_override_, device_);
    f->emit = Buffer<float>(n, device_);
    f->region_emits = Buffer<std::uint8_t>(n, device_);
    intrinsic_glue::emit_weights(device_, gaussians.extras, extra::kCount, extra::kRegion, n,
                                 overridden ? emit_override_on_device_.data() : nullptr, emit_or_region_, f->emit.data(),
                                 f->region_emits.data());
    if (n_glossy > 0) {
      GaussianView plain = traced_view(gaussians, *f);
      plain.extras = nullptr;
      plain.n_extras = 0;
      tracer_.build(plain, f->emit.data());
    }
  }
  // First (with coarse tracing: the representatives of every 2^max_level block) or only pass.
  RaySelection first;
  ReflectionRays first_rays;
  Buffer<float> first_color, first_depth, first_alpha;
  if (coarse) {
    {
      StageTimer t(profile_, device_, times_.rays);
      first = select_block_rays(glossy, W, H, nullptr, cs);
      first_rays = ray_list(first.count, device_);
      gather_rays(glossy, first, first_rays, 0);
    }
    StageTimer t(profile_, device_, times_.trace);
    first_color = Buffer<float>(3 * first.count, device_);
    first_depth = Buffer<float>(first.count, device_);
    first_alpha = Buffer<float>(first.count, device_);
    trace_rays(first_rays, 0, first.count, first_color, first_depth, first_alpha, 0);
  } else {
    StageTimer t(profile_, device_, times_.trace);
    f->rays = std::move(glossy);
    f->ray_color = Buffer<float>(3 * n_glossy, device_);
    f->ray_depth = Buffer<float>(n_glossy, device_);
    f->ray_alpha = Buffer<float>(n_glossy, device_);
    trace_rays(f->rays, 0, n_glossy, f->ray_color, f->ray_depth, f->ray_alpha, 0);
  }

  if (f->use_filter) {
    {
      StageTimer t(profile_, device_, times_.filter);
      const Buffer<float> distance =
          coarse ? representative_distance(glossy, &first, first_depth, first_alpha, W, H, cs.max_level, extent_)
                 : representative_distance(f->rays, nullptr, f->ray_depth, f->ray_alpha, W, H, 0, extent_);
      net_forward(*f, distance, maps);
    }
    if (coarse) {  // the final selection from R_s: the first pass plus the rays it adds
      RaySelection all, added;
      {
        StageTimer t(profile_, device_, times_.rays);
        all = select_block_rays(glossy, W, H, &f->rs, cs);
        added = selection_difference(all, first);
        f->rays = ray_list(all.count, device_);
        gather_rays(glossy, first, f->rays, 0);
        gather_rays(glossy, added, f->rays, first.count);
        if (all.count < n_glossy) f->mass = selection_mass(glossy, all, W, H);
      }
      StageTimer t(profile_, device_, times_.trace);
      f->ray_color = Buffer<float>(3 * all.count, device_);
      f->ray_depth = Buffer<float>(all.count, device_);
      f->ray_alpha = Buffer<float>(all.count, device_);
      device_copy(f->ray_color.data(), device_, first_color.data(), device_, first_color.bytes());
      device_copy(f->ray_depth.data(), device_, first_depth.data(), device_, first_depth.bytes());
      device_copy(f->ray_alpha.data(), device_, first_alpha.data(), device_, first_alpha.bytes());
      trace_rays(f->rays, first.count, added.count, f->ray_color, f->ray_depth, f->ray_alpha, first.count);
    }
  }
  times_.rays_traced = f->rays.count;
  times_.rays_glossy = n_glossy;
  ++ray_totals_.frames;
  ray_totals_.glossy += n_glossy;
  ray_totals_.traced += f->rays.count;
  {
    StageTimer t(profile_, device_, times_.trace);
    traced_to_images(f->rays, W, H, f->ray_color, f->ray_alpha, traced_settings_, f->L_raw, f->V_raw);
  }

  std::optional<StageTimer> filter_timer(std::in_place, profile_, device_, times_.filter);
  if (f->use_filter) {
    Buffer<float> x(4 * hw, device_);
    device_copy(x.data(), device_, f->L_raw.data(), device_, 3 * hw * sizeof(float));
    device_copy(x.data() + 3 * hw, device_, f->V_raw.data(), device_, hw * sizeof(float));
    filter_.forward(x, 4, H, W, g.normal, f->rs, f->filtered, f->mass_or_null());
    f->L = Buffer<float>(3 * hw, device_);
    f->V = Buffer<float>(hw, device_);
    device_copy(f->L.data(), device_, f->filtered.data(), device_, 3 * hw * sizeof(float));
    device_copy(f->V.data(), device_, f->filtered.data() + 3 * hw, device_, hw * sizeof(float));
  } else {
    f->L = f->L_raw.copy_to(device_);
    f->V = f->V_raw.copy_to(device_);
  }
  filter_timer.reset();
  {
    StageTimer t(profile_, device_, times_.shade);
    f->shaded = shade(camera, f->surface, f->L, f->V, env_.mips(), shading_settings_, device_, maps);
  }
  frame_ = std::move(f);
}

void IntrinsicRenderer::backward(const GaussianView& gaussians, const ImageGradients& d, const GaussianGradView& grads) {
  const GBuffer& g = raster_.gbuffer;
  const std::size_t hw = g.pixels();
  const std::size_t ne = std::size_t(g.n_extras);
  Buffer<float> g_alpha = grad_plane(d.alpha, hw, device_), g_depth = grad_plane(d.depth, hw, device_),
                g_normal = grad_plane(d.normal, 3 * hw, device_), g_extras = grad_plane(d.extras, ne * hw, device_);
  GBufferGrad go;
  go.alpha = g_alpha.data();
  go.depth = g_depth.data();
  go.median_depth = d.median_depth;
  go.normal = g_normal.data();
  go.extras = g_extras.data();
  times_.shade_back = times_.filter_back = times_.trace_back = times_.raster_back = 0;
  {
    StageTimer t(profile_, device_, times_.raster_back);
    backward_detached_extras(gaussians, raster_.state, d.extras_detached, grads);
  }
  if (!frame_) {  // radiance warm-up: the colour is the rasterized one
    if (d.base_color) throw Error("intrinsic renderer", "dL/dD given while D is the colour (warm-up): add it to dL/dcolour");
    go.color = d.color;
    StageTimer t(profile_, device_, times_.raster_back);
    rasterize_backward(gaussians, raster_.state, go, grads);
    return;
  }
  Frame& f = *frame_;
  const std::size_t n = f.rays.count;
  Buffer<float> g_color = grad_plane(d.base_color, 3 * hw, device_);  // dL/dD from losses on D itself
  go.color = g_color.data();
  SurfaceGrads sg;
  sg.color = g_color.data();
  sg.alpha = g_alpha.data();
  sg.depth = g_depth.data();
  sg.normal = g_normal.data();
  sg.region = g_extras.data() + std::size_t(kChannels.region) * hw;
  sg.f0 = g_extras.data() + std::size_t(kChannels.f0) * hw;
  sg.roughness = g_extras.data() + std::size_t(kChannels.roughness) * hw;
  if (!d.color) throw Error("intrinsic renderer", "backward needs dL/dcolour");
  const Buffer<float> dC = grad_plane(d.color, 3 * hw, device_);

  Buffer<float> dL, dV;
  {
    StageTimer t(profile_, device_, times_.shade_back);
    shade_backward(f.camera, f.surface, f.L, f.V, env_.mips(), shading_settings_, dC, sg, dL, dV, env_.mip_grads(), device_);
    env_.backward();
  }
  std::optional<StageTimer> filter_timer(std::in_place, profile_, device_, times_.filter_back);

  Buffer<float> dL_raw, dV_raw;
  if (f.use_filter) {
    Buffer<float> gout(4 * hw, device_), gx(4 * hw, device_), grs(hw, device_);
    device_copy(gout.data(), device_, dL.data(), device_, 3 * hw * sizeof(float));
    if (dV.size() == hw)
      device_copy(gout.data() + 3 * hw, device_, dV.data(), device_, hw * sizeof(float));
    else
      device_memset_zero(device_, gout.data() + 3 * hw, hw * sizeof(float));
    gx.fill_zero();
    grs.fill_zero();
    filter_.backward(gout, &gx, &grs);
    Buffer<float> gin(3 * hw, device_);
    gin.fill_zero();
    net_.backward(grs, &gin);
    // Only the roughness input is a function of the Gaussians that we differentiate (depths are constants).
    add_into(device_, gin.data(), g_extras.data() + std::size_t(extra::kRoughness) * hw, hw);
    dL_raw = Buffer<float>(3 * hw, device_);
    dV_raw = Buffer<float>(hw, device_);
    device_copy(dL_raw.data(), device_, gx.data(), device_, 3 * hw * sizeof(float));
    device_copy(dV_raw.data(), device_, gx.data() + 3 * hw, device_, hw * sizeof(float));
  } else {
    dL_raw = std::move(dL);
    dV_raw = std::move(dV);
  }

  filter_timer.reset();
  std::optional<StageTimer> trace_timer(std::in_place, profile_, device_, times_.trace_back);
  if (n > 0) {
    Buffer<float> dcolor, dalpha;
    traced_to_images_backward(f.rays, g.width, g.height, f.ray_color, f.ray_alpha, traced_settings_, dL_raw, dV_raw,
                              dcolor, dalpha);
    Buffer<float> dorig(3 * n, device_), ddir(3 * n, device_), demit(std::size_t(gaussians.count), device_);
    demit.fill_zero();
    TraceOutputGrads tg;
    tg.color = dcolor.data();
    tg.alpha = dalpha.data();
    GaussianGradView tgrads = grads;
    tgrads.extras = nullptr;
    tgrads.mean2d_grad_norm = nullptr;
    tracer_.backward({f.rays.origins.data(), f.rays.directions.data(), n}, tg, tgrads, {dorig.data(), ddir.data()},
                     demit.data());
    reflection_rays_backward(f.camera, f.surface, shading_settings_, f.rays, dorig.data(), ddir.data(), sg, device_);
    // dL/d(emit) is dL/d(region weight) of each Gaussian (activated space, where grads.extras lives).
    if (grads.extras)
      intrinsic_glue::add_emit_grads(device_, demit.data(),
                                     f.region_emits.size() == demit.size() ? f.region_emits.data() : nullptr,
                                     demit.size(), extra::kCount, extra::kRegion, grads.extras);
  }
  trace_timer.reset();
  StageTimer t(profile_, device_, times_.raster_back);
  rasterize_backward(gaussians, raster_.state, go, grads);
}

void IntrinsicRenderer::step_own_parameters(int iteration) {
  if (!frame_) return;  // nothing flowed into them this iteration
  if (config_.intrinsic.lr_env == 0 && config_.intrinsic.lr_net == 0) {  // frozen (stage 2)
    env_.zero_grad();
    net_.zero_grad();
    return;
  }
  const int end = std::max(config_.iterations, shading_from_ + 1);
  const float lr_env = exponential_lr(iteration - shading_from_, config_.intrinsic.lr_env, config_.intrinsic.lr_env_final,
                                      end - shading_from_);
  env_adam_.step(env_.params(), env_.grads(), lr_env, "environment map");
  env_.zero_grad();
  if (frame_->use_filter) {
    const int ease_until = std::max(config_.shading_phase_iteration(config_.intrinsic.net_ease_until), shading_from_ + 1);
    const float t = std::clamp(float(iteration - shading_from_) / float(ease_until - shading_from_), 0.0f, 1.0f);
    net_adam_.step(net_.params(), net_.grads(), config_.intrinsic.lr_net * t, "roughness net");
    net_.zero_grad();
  }
  env_.update();  // also checks the parameters are finite
}

std::string IntrinsicRenderer::save_own_state() const {
  OwnStateWriter w;
  w.header(env_.resolution(), int(net_.param_count()));
  w.buffer(env_.params());
  w.adam(env_adam_);
  w.buffer(net_.params());
  w.adam(net_adam_);
  return w.bytes();
}

void IntrinsicRenderer::load_own_state(const std::string& bytes, const std::string& source) {
  OwnStateReader r(bytes, source);
  r.header(env_.resolution(), int(net_.param_count()));
  r.buffer(env_.params());
  r.adam(env_adam_);
  r.buffer(net_.params());
  r.adam(net_adam_);
  r.finish();
  env_.update();
}

IntrinsicMaps IntrinsicRenderer::render_maps(const GaussianView& gaussians, const Camera& camera) {
  const bool was = shading_;
  shading_ = false;
  forward(gaussians, camera);
  shading_ = was;
  shade_forward(gaussians, camera, true);
  const Frame& f = *frame_;
  IntrinsicMaps m;
  m.width = raster_.gbuffer.width;
  m.height = raster_.gbuffer.height;
  m.color = f.shaded.color.to_host();
  m.sh_color = raster_.gbuffer.color.to_host();
  m.glossy = f.shaded.glossy.to_host();
  m.env = f.shaded.env_radiance.to_host();
  m.indirect = f.L.to_host();
  m.visibility = f.V.to_host();
  if (f.use_filter) {
    m.screen_roughness = f.rs.to_host();
    m.indirect_traced = f.L_raw.to_host();
    m.visibility_traced = f.V_raw.to_host();
  }
  m.rays = f.rays.count;
  m.glossy_pixels = f.glossy;
  return m;
}

}  // namespace goris

namespace goris {

std::vector<float> IntrinsicRenderer::reflected_label(const GaussianView& gaussians, const Camera& camera,
                                                     float fresnel_reference) {
  if (!(fresnel_reference > 0) || !std::isfinite(fresnel_reference))
    throw Error("lighting-aware mask", "the Fresnel reference must be finite and > 0");
  const bool was = shading_;
  shading_ = false;
  forward(gaussians, camera);
  shading_ = was;
  shade_forward(gaussians, camera, false);
  const Frame& f = *frame_;
  const GBuffer& g = raster_.gbuffer;
  const int W = g.width, H = g.height;
  const std::size_t hw = g.pixels(), n = f.rays.count;
  std::vector<float> label(hw, 0.0f);
  if (n > 0) {
    Buffer<float> ray_extras(n * std::size_t(extra::kCount), device_), ray_alpha(n, device_);
    tracer_.build(traced_view(gaussians, *frame_), f.emit.data());
    TraceOutputs out;
    out.extras = ray_extras.data();
    out.alpha = ray_alpha.data();
    tracer_.trace({f.rays.origins.data(), f.rays.directions.data(), n}, out);
    const std::vector<float> ex = ray_extras.to_host();
    const std::vector<std::uint32_t> pix = f.rays.pixels.to_host();
    for (std::size_t i = 0; i < n; ++i) label[pix[i]] = ex[i * extra::kCount + extra::kLabel];
  }
  if (f.use_filter) {
    ssf::GlossyFilter<float> filter(filter_.config());
    Buffer<float> filtered;
    filter.forward(Buffer<float>(label, device_), 1, H, W, g.normal, f.rs, filtered, f.mass_or_null());
    label = filtered.to_host();
  }
  // Weight like the glossy term: (1 - M) F, F = F0 + (1 - F0)(1 - cos)^5 with cos = n . (-view ray), taken
  // relative to fresnel_reference and capped at 1.
  const std::vector<float> ex = g.extras.to_host(), normal = g.normal.to_host(), alpha = g.alpha.to_host();
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t p = std::size_t(y) * W + x;
      if (alpha[p] <= shading_settings_.min_alpha) {
        label[p] = 0.0f;
        continue;
      }
      const float a = alpha[p];
      glm::vec3 nn(normal[p], normal[hw + p], normal[2 * hw + p]);
      const float len = glm::length(nn);
      if (len < 1e-8f) {
        label[p] = 0.0f;
        continue;
      }
      nn /= len;
      const glm::vec3 v = glm::normalize(glm::vec3((x + 0.5f - camera.cx) / camera.fx, (y + 0.5f - camera.cy) / camera.fy, 1.0f));
      const float c = std::clamp(-glm::dot(nn, v), 0.0f, 1.0f);
      const float schlick = std::pow(1.0f - c, 5.0f);
      float fres = 0;
      for (int k = 0; k < 3; ++k) {
        const float f0 = std::clamp(ex[std::size_t(extra::kFresnel + k) * hw + p] / a, 0.0f, 1.0f);
        fres += (f0 + (1 - f0) * schlick) / 3.0f;
      }
      const float m = std::clamp(ex[std::size_t(extra::kRegion) * hw + p] / a, 0.0f, 1.0f);
      label[p] *= (1 - m) * std::min(1.0f, fres / fresnel_reference);
    }
  return label;
}

}  // namespace goris
