#include "train/config/train_config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "core/util/number_text.h"
#include "train/config/config_migration.h"

namespace goris {

namespace {

// The run length the schedule's iteration points are given for (3DGS's full schedule); shorter runs scale
// them (scaled_iteration, shading_phase_iteration) and raise the colour's rate (sh_dc_rate).
constexpr int kFullSchedule = 30000;

// The one-line documentation of a user-facing setting (ConfigKeyInfo) and the heading it is listed under;
// empty for the others.
struct Doc {
  const char* section = "";
  const char* text = "";
};

// One list of (name, member, documentation) serves writing, reading and the reference page, so that they
// cannot drift apart. The user-facing settings carry their documentation here, beside their key.
template <class Config, class F>
void visit_fields(Config& c, F&& visit) {
  const auto f = [&](const char* name, auto& member, Doc doc = {}) { visit(name, member, doc); };
  f("mode", c.mode,
    {"Run", "What to train: `radiance` (SH colour), `intrinsic` (stage 1: materials, traced reflections and "
            "shading after a radiance warm-up) or `auto` (intrinsic for a glossy scene, radiance otherwise). Also `--mode`."});
  f("iterations", c.iterations,
    {"Run", "Training iterations; the schedule points of the full 30000-iteration schedule scale with it. Also "
            "`--iters`."});
  f("seed", c.seed,
    {"Run", "Random seed of the initial points, the view order and the splits. Also `--seed`."});
  f("device", c.device,
    {"Run", "Where to train: `auto` (CUDA when a device is usable, else the CPU), `cpu` or `cuda`. Also "
            "`--device`."});
  f("data", c.input.data);
  f("data_views", c.input.data_views);
  f("downscale", c.input.downscale,
    {"Data", "Divide the image size by this factor (>= 1). Also `--downscale`."});
  f("resolution", c.input.resolution,
    {"Data", "Train at this image width in pixels, the height keeping the aspect (0 = use `downscale`). Also "
             "`--resolution`."});
  f("background", c.input.background,
    {"Data", "Colour [r, g, b] that RGBA images are composited on; also the renders' background."});
  f("use_glossy_masks", c.input.use_glossy_masks,
    {"Data", "Use the data set's glossy masks; without them `--mode auto` detects glossy regions from the photos."});
  f("use_object_masks", c.input.use_object_masks);
  f("max_train_views", c.input.max_train_views,
    {"Data", "Train on at most this many views, spread evenly over the data set (0 = all)."});
  f("glossy_mask_dir", c.input.glossy_mask_dir);
  f("auto_detect_glossy", c.input.auto_detect_glossy);
  f("random_init_points", c.init.random_points,
    {"Initialisation", "Random initial points when the data set has no SfM points. Also `--init-points`."});
  f("init_model", c.init.model,
    {"Initialisation", "Model file to start from (3DGS PLY, compressed PLY, SPZ, .splat, GLB) instead of SfM or "
                       "random points (empty = none). Also `--init`."});
  f("random_init_box_ratio", c.init.random_box_ratio);
  f("lr_position_init", c.lr.position_init);
  f("lr_position_final", c.lr.position_final);
  f("lr_position_max_steps", c.lr.position_max_steps);
  f("lr_sh_dc", c.lr.sh_dc);
  f("lr_sh_dc_short_run_power", c.lr.sh_dc_short_run_power);
  f("lr_sh_rest", c.lr.sh_rest);
  f("lr_opacity", c.lr.opacity);
  f("lr_scale", c.lr.scale);
  f("lr_rotation", c.lr.rotation);
  f("lr_materials", c.lr.materials);
  f("lr_region", c.lr.region);
  f("lr_label", c.lr.label);
  f("lambda_ssim", c.loss.lambda_ssim,
    {"Losses", "Weight l of the colour loss (1 - l) L1 + l (1 - SSIM)."});
  f("alpha_weight", c.loss.alpha_weight,
    {"Losses", "L1 between the rendered alpha and the images' alpha channel (0 = off)."});
  f("depth_normal_weight", c.loss.depth_normal_weight,
    {"Losses", "RaDe-GS depth-normal consistency, from iteration `depth_normal_from` (0 = off)."});
  f("depth_normal_from", c.loss.depth_normal_from);
  f("depth_normal_median_ratio", c.loss.depth_normal_median_ratio);
  f("depth_distortion_weight", c.loss.depth_distortion_weight,
    {"Losses", "2DGS depth distortion (0 = off)."});
  f("depth_distortion_from", c.loss.depth_distortion_from);
  f("depth_distortion_until", c.loss.depth_distortion_until);
  f("depth_distortion_glossy", c.loss.depth_distortion_glossy);
  f("sh_degree_interval", c.sh.degree_interval);
  f("max_sh_degree", c.sh.max_degree,
    {"Losses", "Highest spherical-harmonics degree of the colour, 0 to 3."});
  f("densify_from_iter", c.densify.from_iter,
    {"Densification", "First densification (clone, split, prune) at this iteration."});
  f("densify_until_iter", c.densify.until_iter,
    {"Densification", "No densification after this iteration (of the full schedule; see `densify_until_fraction`)."});
  f("densify_interval", c.densify.interval,
    {"Densification", "Densify every this many iterations."});
  f("densify_until_fraction", c.densify.until_fraction,
    {"Densification", "Densification also stops at this fraction of the run, so that a short run ends with pure "
                      "optimisation."});
  f("densify_grad_threshold", c.densify.grad_threshold,
    {"Densification", "Clone or split Gaussians whose view-averaged screen-space gradient exceeds this."});
  f("percent_dense", c.densify.percent_dense);
  f("split_count", c.densify.split_count);
  f("prune_min_opacity", c.densify.min_opacity,
    {"Densification", "Prune Gaussians less opaque than this."});
  f("opacity_reset_interval", c.densify.opacity_reset_interval,
    {"Densification", "Reset opacities every this many iterations of a full densification window."});
  f("reset_opacity", c.densify.reset_opacity);
  f("prune_max_screen_radius", c.densify.max_screen_radius);
  f("prune_max_world_scale", c.densify.max_world_scale);
  f("filter_3d", c.anti_aliasing.filter_3d,
    {"Anti-aliasing", "Mip-Splatting 3D filter."});
  f("filter_3d_interval", c.anti_aliasing.filter_3d_interval);
  f("filter_2d", c.anti_aliasing.filter_2d,
    {"Anti-aliasing", "Mip-Splatting 2D filter (off: the 3DGS 0.3-pixel dilation)."});
  f("intrinsic_warmup", c.intrinsic.warmup,
    {"Intrinsic mode", "Radiance-only iterations before shading starts (of the full schedule; a short run keeps "
                       "`intrinsic_warmup_min_fraction` of itself)."});
  f("intrinsic_warmup_min_fraction", c.intrinsic.warmup_min_fraction);
  f("intrinsic_env_resolution", c.intrinsic.env_resolution,
    {"Intrinsic mode", "Face size of the learned environment cube map (a power of two)."});
  f("intrinsic_env_initial", c.intrinsic.env_initial);
  f("intrinsic_env_distance", c.intrinsic.env_distance,
    {"Intrinsic mode", "The environment on a sphere of this radius x the cameras' mean distance to their focus (0 "
                       "= at infinity, for outdoor captures)."});
  f("intrinsic_env_center", c.intrinsic.env_center);
  f("intrinsic_env_radius", c.intrinsic.env_radius);
  f("intrinsic_init_roughness", c.intrinsic.init_roughness);
  f("intrinsic_init_fresnel", c.intrinsic.init_fresnel);
  f("intrinsic_lr_env", c.intrinsic.lr_env);
  f("intrinsic_lr_env_final", c.intrinsic.lr_env_final);
  f("intrinsic_lr_net", c.intrinsic.lr_net);
  f("intrinsic_net_ease_until", c.intrinsic.net_ease_until);
  f("intrinsic_screen_space_filter", c.intrinsic.screen_space_filter,
    {"Intrinsic mode", "Reflections and visibility through the screen-space glossy filter."});
  f("intrinsic_net_hidden_layers", c.intrinsic.net_hidden_layers);
  f("intrinsic_ray_offset", c.intrinsic.ray_offset);
  f("intrinsic_trace_glossy_transparent", c.intrinsic.trace_glossy_transparent);
  f("intrinsic_divide_opaque", c.intrinsic.divide_opaque);
  f("intrinsic_prune_mirror_world", c.intrinsic.prune_mirror_world,
    {"Intrinsic mode", "Remove the Gaussians seen only behind glossy surfaces when shading starts; the value is "
                       "the depth tolerance (0 = off)."});
  f("intrinsic_prune_mirror_world_repeat", c.intrinsic.prune_mirror_world_repeat);
  f("intrinsic_glossy_plane", c.intrinsic.glossy_plane);
  f("intrinsic_glossy_plane_prune_sinkers", c.intrinsic.glossy_plane_prune_sinkers);
  f("intrinsic_glossy_plane_align", c.intrinsic.glossy_plane_align);
  f("intrinsic_coarse_tracing", c.intrinsic.coarse_tracing,
    {"Intrinsic mode", "One reflection ray per pixel block where the glossy filter blurs anyway (faster)."});
  f("intrinsic_coarse_max_level", c.intrinsic.coarse_max_level);
  f("intrinsic_normal_prior", c.intrinsic.normal_prior,
    {"Intrinsic mode", "Weight of the normal prior, decaying to `intrinsic_normal_prior_final`."});
  f("intrinsic_normal_prior_final", c.intrinsic.normal_prior_final);
  f("intrinsic_normal_prior_until", c.intrinsic.normal_prior_until);
  f("intrinsic_material_losses_in_warmup", c.intrinsic.material_losses_in_warmup);
  f("intrinsic_emit", c.intrinsic.emit,
    {"Intrinsic mode", "Which Gaussians emit into traced rays: `region` (the learned region weight), `mask` (from "
                       "the glossy masks) or `max`."});
  f("intrinsic_smoothness", c.intrinsic.smoothness,
    {"Intrinsic mode", "Edge-aware smoothness of F0, roughness and normal on the glossy mask."});
  f("intrinsic_region", c.intrinsic.region,
    {"Intrinsic mode", "Weight of the region loss, the learned region weight against the glossy masks."});
  f("intrinsic_label", c.intrinsic.label,
    {"Intrinsic mode", "Weight of the object-label loss against the object masks."});
  f("intrinsic_normals", c.intrinsic.normals,
    {"Intrinsic mode", "Folder of normal-prior maps (empty = none). Also `--normals`."});
  f("intrinsic_auto_mask_fraction", c.intrinsic.auto_mask_fraction);
  f("intrinsic_detect_neighbours", c.intrinsic.detect_neighbours);
  f("intrinsic_detect_threshold", c.intrinsic.detect_threshold);
  f("intrinsic_detect_depth_tolerance", c.intrinsic.detect_depth_tolerance);
  f("intrinsic_detect_search_radius", c.intrinsic.detect_search_radius);
  f("intrinsic_detect_depth_window", c.intrinsic.detect_depth_window);
  f("intrinsic_detect_morph_radius", c.intrinsic.detect_morph_radius);
  f("intrinsic_detect_fraction", c.intrinsic.detect_fraction);
  f("intrinsic_detect_width", c.intrinsic.detect_width);
  f("intrinsic_detect_after", c.intrinsic.detect_after);
  f("intrinsic_detect_settled", c.intrinsic.detect_settled);
  f("intrinsic_detect_plane_tolerance", c.intrinsic.detect_plane_tolerance);
  f("intrinsic_detect_mirror_world", c.intrinsic.detect_mirror_world);
  f("inpaint_appearance_weight", c.inpaint.appearance_weight);
  f("inpaint_material_weight", c.inpaint.material_weight);
  f("nan_policy", c.nan.policy,
    {"Bookkeeping", "On a non-finite loss or gradient: `recover` (skip the step, lower the learning rates) or "
                    "`stop`."});
  f("nan_lr_factor", c.nan.lr_factor);
  f("nan_max_skips", c.nan.max_skips);
  f("log_interval", c.bookkeeping.log_interval);
  f("checkpoint_interval", c.bookkeeping.checkpoint_interval,
    {"Bookkeeping", "Checkpoint every this many iterations (0 = only at the end or when stopped). Also "
                    "`--checkpoint-every`."});
  f("keep_checkpoints", c.bookkeeping.keep_checkpoints,
    {"Bookkeeping", "Older checkpoint files beyond this many are deleted."});
}

nlohmann::json vec_json(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

}  // namespace

void TrainConfig::validate(const std::string& what) const {
  auto fail = [&](const std::string& p) { throw Error(what, p); };
  if (iterations < 1) fail("iterations must be at least 1");
  if (!(input.downscale >= 1.0f)) fail("downscale must be >= 1");
  if (input.resolution < 0) fail("resolution must be positive (or 0 for none)");
  if (input.max_train_views < 0) fail("max_train_views must be >= 0 (0 = all views)");
  if (init.random_points < 1 || init.random_points > kMaxRandomInitPoints)
    fail("random_init_points must be from 1 to " + std::to_string(kMaxRandomInitPoints) +
         " (each point is a Gaussian with its optimiser state, about 1 KB)");
  if (!(init.random_box_ratio > 0)) fail("random_init_box_ratio must be positive");
  if (!(loss.lambda_ssim >= 0 && loss.lambda_ssim <= 1)) fail("lambda_ssim must lie in [0, 1]");
  if (!(loss.depth_normal_weight >= 0)) fail("depth_normal_weight must be >= 0");
  if (!(loss.alpha_weight >= 0) || !std::isfinite(loss.alpha_weight))
    fail("alpha_weight must be finite and >= 0 (0 = off)");
  if (!(loss.depth_distortion_weight >= 0 && std::isfinite(loss.depth_distortion_weight)))
    fail("depth_distortion_weight must be finite and >= 0");
  if (loss.depth_distortion_from < 0) fail("depth_distortion_from must be >= 0");
  if (loss.depth_distortion_until < 0 ||
      (loss.depth_distortion_until > 0 && loss.depth_distortion_until <= loss.depth_distortion_from))
    fail("depth_distortion_until must be 0 (to the end) or after depth_distortion_from");
  if (!(loss.depth_distortion_glossy >= 0 && loss.depth_distortion_glossy <= 1))
    fail("depth_distortion_glossy must lie in [0, 1]");
  if (!(loss.depth_normal_median_ratio >= 0 && loss.depth_normal_median_ratio <= 1))
    fail("depth_normal_median_ratio must lie in [0, 1]");
  if (sh.degree_interval < 1) fail("sh_degree_interval must be at least 1");
  if (sh.max_degree < 0 || sh.max_degree > 3) fail("max_sh_degree must lie in 0..3");
  if (densify.interval < 1) fail("densify_interval must be at least 1");
  if (!(densify.until_fraction >= 0 && densify.until_fraction <= 1)) fail("densify_until_fraction must lie in [0, 1]");
  if (densify.opacity_reset_interval < 1) fail("opacity_reset_interval must be at least 1");
  if (densify.split_count < 1 || densify.split_count > 8) fail("split_count must lie in 1..8");
  if (!(densify.min_opacity >= 0 && densify.min_opacity < 1)) fail("prune_min_opacity must lie in [0, 1)");
  if (!(densify.reset_opacity > 0 && densify.reset_opacity < 1)) fail("reset_opacity must lie in (0, 1)");
  if (anti_aliasing.filter_3d_interval < 1) fail("filter_3d_interval must be at least 1");
  if (bookkeeping.log_interval < 1) fail("log_interval must be at least 1");
  if (bookkeeping.checkpoint_interval < 0) fail("checkpoint_interval must be >= 0");
  if (bookkeeping.keep_checkpoints < 1) fail("keep_checkpoints must be at least 1");
  if (!(inpaint.appearance_weight >= 0) || !(inpaint.material_weight >= 0))
    fail("inpaint_appearance_weight and inpaint_material_weight must be >= 0");
  if (!(nan.lr_factor > 0 && nan.lr_factor <= 1)) fail("nan_lr_factor must lie in (0, 1]");
  if (nan.max_skips < 1) fail("nan_max_skips must be at least 1");
  const IntrinsicSettings& in = intrinsic;
  if (in.warmup < 0) fail("intrinsic_warmup must be >= 0");
  if (!(in.warmup_min_fraction >= 0 && in.warmup_min_fraction <= 1))
    fail("intrinsic_warmup_min_fraction must be in [0, 1]");
  if (in.env_resolution < 1 || in.env_resolution > 4096 || (in.env_resolution & (in.env_resolution - 1)))
    fail("intrinsic_env_resolution must be a power of two in 1..4096");
  if (!(in.env_initial > 0)) fail("intrinsic_env_initial must be positive");
  if (!(in.init_roughness > 0 && in.init_roughness < 1) || !(in.init_fresnel > 0 && in.init_fresnel < 1))
    fail("intrinsic_init_roughness and intrinsic_init_fresnel must lie in (0, 1) (sigmoid-activated)");
  if (in.net_hidden_layers < 0 || in.net_hidden_layers > 16) fail("intrinsic_net_hidden_layers must lie in 0..16");
  if (!(in.ray_offset >= 0)) fail("intrinsic_ray_offset must be >= 0");
  if (!(in.trace_glossy_transparent >= 0 && in.trace_glossy_transparent <= 1))
    fail("intrinsic_trace_glossy_transparent must be in [0, 1]");
  if (!(in.env_distance >= 0) || !std::isfinite(in.env_distance) || !(in.env_radius >= 0) ||
      !std::isfinite(in.env_radius))
    fail("intrinsic_env_distance and intrinsic_env_radius must be finite and >= 0 (0 = at infinity)");
  if (!std::isfinite(in.env_center.x) || !std::isfinite(in.env_center.y) || !std::isfinite(in.env_center.z))
    fail("intrinsic_env_center must be finite");
  if (in.coarse_max_level < 1 || in.coarse_max_level > 3) fail("intrinsic_coarse_max_level must lie in 1..3");
  if (!(in.auto_mask_fraction >= 0 && in.auto_mask_fraction <= 1) || !(in.detect_fraction >= 0 && in.detect_fraction <= 1))
    fail("intrinsic_auto_mask_fraction and intrinsic_detect_fraction must lie in [0, 1]");
  if (in.detect_neighbours < 1 || in.detect_neighbours > 16) fail("intrinsic_detect_neighbours must lie in 1..16");
  if (!(in.detect_threshold >= 0) || !std::isfinite(in.detect_threshold))
    fail("intrinsic_detect_threshold must be finite and >= 0");
  if (!(in.detect_depth_tolerance > 0) || !std::isfinite(in.detect_depth_tolerance))
    fail("intrinsic_detect_depth_tolerance must be finite and positive");
  if (in.detect_search_radius < 0 || in.detect_search_radius > 8) fail("intrinsic_detect_search_radius must lie in 0..8");
  if (!(in.prune_mirror_world >= 0) || !std::isfinite(in.prune_mirror_world))
    fail("intrinsic_prune_mirror_world must be finite and >= 0 (0 = off)");
  if (in.detect_depth_window < 0 || in.detect_depth_window > 8) fail("intrinsic_detect_depth_window must lie in 0..8");
  if (in.detect_morph_radius < 0 || in.detect_morph_radius > 8) fail("intrinsic_detect_morph_radius must lie in 0..8");
  if (in.detect_width < 0) fail("intrinsic_detect_width must be >= 0 (0 = the training size)");
  if (in.detect_after < 0) fail("intrinsic_detect_after must be >= 0");
  if (in.detect_settled < 0) fail("intrinsic_detect_settled must be >= 0");
  if (!(in.detect_plane_tolerance >= 0) || !std::isfinite(in.detect_plane_tolerance))
    fail("intrinsic_detect_plane_tolerance must be finite and >= 0");
  for (float w : {in.lr_env, in.lr_env_final, in.lr_net, in.normal_prior, in.normal_prior_final, in.smoothness,
                  in.region, in.label})
    if (!(w >= 0) || !std::isfinite(w)) fail("intrinsic learning rates and loss weights must be finite and >= 0");
  for (float lr : {lr.position_init, lr.position_final, lr.sh_dc, lr.sh_rest, lr.opacity, lr.scale, lr.rotation,
                   lr.materials, lr.region, lr.label})
    if (!(lr >= 0)) fail("learning rates must be >= 0");
  if (!(lr.sh_dc_short_run_power >= 0 && lr.sh_dc_short_run_power <= 1))
    fail("lr_sh_dc_short_run_power must be in [0, 1]");
}

int TrainConfig::scaled_iteration(int full) const {
  if (iterations >= kFullSchedule) return full;
  return int(std::lround(double(full) * double(iterations) / double(kFullSchedule)));
}

float TrainConfig::sh_dc_rate() const {
  // Measured at 2K and 8K iterations; shorter runs keep 2K's factor (at 60 iterations, x22 left the
  // embedded scene's target no hole of its own to inpaint).
  constexpr double kShortest = 2000.0;
  if (iterations >= kFullSchedule || lr.sh_dc_short_run_power == 0.0f) return lr.sh_dc;
  const double run = std::max(double(iterations), kShortest);
  return float(double(lr.sh_dc) * std::pow(double(kFullSchedule) / run, double(lr.sh_dc_short_run_power)));
}

int TrainConfig::densify_until() const {
  return std::min(densify.until_iter, int(double(densify.until_fraction) * iterations));
}

int TrainConfig::opacity_reset_every() const {
  const int until = densify_until();
  if (until >= densify.until_iter || densify.until_iter <= 0) return densify.opacity_reset_interval;
  const int step = std::max(densify.interval, 1);
  const double scaled = double(densify.opacity_reset_interval) * double(std::max(until, 0)) / double(densify.until_iter);
  return std::max(1, int(std::lround(scaled / step))) * step;
}

int TrainConfig::shading_from() const {
  const int floor = int(std::lround(double(intrinsic.warmup_min_fraction) * double(iterations)));
  return std::max(scaled_iteration(intrinsic.warmup), std::min(intrinsic.warmup, floor));
}

bool TrainConfig::prunes_mirror_world_after(int it, bool densified) const {
  if (mode != TrainMode::Intrinsic || !(intrinsic.prune_mirror_world > 0)) return false;
  const int from = shading_from();
  return it == from || (intrinsic.prune_mirror_world_repeat && densified && it > from);
}

bool TrainConfig::depth_distortion_at(int it) const {
  return loss.depth_distortion_weight > 0 && it > scaled_iteration(loss.depth_distortion_from) &&
         (loss.depth_distortion_until == 0 || it <= scaled_iteration(loss.depth_distortion_until));
}

int TrainConfig::shading_phase_iteration(int full) const {
  const int from = shading_from();
  if (full <= intrinsic.warmup) return from;
  if (intrinsic.warmup >= kFullSchedule) return std::max(from, std::min(full, iterations));  // no phase to map onto
  if (iterations >= kFullSchedule) return full;  // the schedule as given (shading_from() is the warm-up itself)
  const double t = double(full - intrinsic.warmup) / double(kFullSchedule - intrinsic.warmup);
  return from + int(std::lround(t * double(std::max(iterations - from, 0))));
}

void to_json(nlohmann::json& j, const TrainConfig& c) {
  j = nlohmann::json::object();
  j["config_version"] = kConfigVersion;
  visit_fields(c, [&](const char* name, const auto& v, Doc) {
    using T = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<T, glm::vec3>)
      j[name] = vec_json(v);
    else if constexpr (std::is_enum_v<T>)
      j[name] = enum_name(v);
    else
      j[name] = v;
  });
}

namespace {

// One setting read without silent conversion (core/util/number_text.h): a whole number within its type's
// limits (10000000000 is refused, not wrapped into an int), a finite number for a real setting ("nan" is
// named as such), true/false, a string. Throws goris::Error with what is expected and what was given.
template <class T>
void read_field(const nlohmann::json& x, T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    if (!x.is_boolean()) throw Error("must be true or false, got " + x.dump());
    v = x.get<bool>();
  } else if constexpr (std::is_integral_v<T>) {
    const long double lo = std::numeric_limits<T>::lowest(), hi = std::numeric_limits<T>::max();
    long double d = 0;
    bool whole = true;
    if (x.is_number_unsigned())
      d = static_cast<long double>(x.get<std::uint64_t>());
    else if (x.is_number_integer())
      d = static_cast<long double>(x.get<std::int64_t>());
    else if (x.is_number_float() && std::floor(x.get<double>()) == x.get<double>())
      d = x.get<double>();
    else
      whole = false;
    if (!whole || d < lo || d > hi)
      throw Error("must be a whole number from " + limit_text(lo) + " to " + limit_text(hi) + ", got " + x.dump());
    v = static_cast<T>(d);
  } else if constexpr (std::is_floating_point_v<T>) {
    if (x.is_string() && names_non_finite_number(x.get<std::string>()))
      throw Error("is " + x.get<std::string>() + ": NaN and infinity are not allowed, a finite number is needed");
    const double hi = double(std::numeric_limits<T>::max());
    if (!x.is_number() || std::fabs(x.get<double>()) > hi)
      throw Error("must be a number from " + limit_text(-hi) + " to " + limit_text(hi) + ", got " + x.dump());
    v = static_cast<T>(x.get<double>());
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!x.is_string()) throw Error("must be a string (in quotes), got " + x.dump());
    v = x.get<std::string>();
  } else if constexpr (std::is_enum_v<T>) {
    const std::optional<T> e = x.is_string() ? enum_from_name<T>(x.get<std::string>()) : std::nullopt;
    if (!e) throw Error("must be " + enum_choices<T>() + ", got " + x.dump());
    v = *e;
  } else {
    v = x.get<T>();
  }
}

}  // namespace

void from_json(const nlohmann::json& file, TrainConfig& c) {
  if (!file.is_object()) throw Error("training configuration: expected a JSON object");
  nlohmann::json j = file;
  migrate_config_json(j);
  std::set<std::string> known = {"config_version"};
  visit_fields(c, [&](const char* name, auto& v, Doc) {
    known.insert(name);
    if (!j.contains(name)) return;
    const nlohmann::json& x = j.at(name);
    try {
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, glm::vec3>) {
        if (!x.is_array() || x.size() != 3) throw Error("expected 3 numbers");
        for (int k = 0; k < 3; ++k) v[k] = x.at(k).get<float>();
      } else {
        read_field(x, v);
      }
    } catch (const Error& e) {
      throw Error(std::string("training configuration: '") + name + "' " + e.what());
    } catch (const std::exception& e) {
      throw Error(std::string("training configuration: key '") + name + "' has the wrong type (" + e.what() + ")");
    }
  });
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) throw Error("training configuration: unknown key '" + it.key() + "'");
}

void apply_config_overrides(const std::vector<std::string>& sets, TrainConfig& config, const std::string& label) {
  nlohmann::json j = config;
  for (const std::string& kv : sets) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw Error(label + " " + kv + ": expected KEY=VALUE");
    const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
    if (key == "config_version")
      throw Error(label + " " + kv + ": 'config_version' is the version of config.json's layout, not a setting");
    if (const ConfigMigration* dropped = dropped_config_key(key); dropped && !j.contains(key))
      throw Error(label + " " + kv + ": '" + key + "' was removed: " + dropped->reason);
    if (!j.contains(key)) throw Error(label + " " + kv + ": unknown setting '" + key + "' (see config.json of a run)");
    nlohmann::json v = nlohmann::json::parse(value, nullptr, false);
    j[key] = v.is_discarded() ? nlohmann::json(value) : v;
  }
  try {
    from_json(j, config);
  } catch (const Error& e) {
    throw Error(label + ": " + e.what());
  }
}

namespace {

std::string real_text(float v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general);
  return std::string(buf, r.ptr);
}

template <class T>
ConfigKeyInfo key_info(const char* name, const T& v, Doc doc) {
  ConfigKeyInfo k{name, "", "", doc.section, doc.text};
  if constexpr (std::is_same_v<T, bool>) {
    k.type = "true/false", k.default_value = v ? "true" : "false";
  } else if constexpr (std::is_integral_v<T>) {
    k.type = "whole number", k.default_value = std::to_string(v);
  } else if constexpr (std::is_floating_point_v<T>) {
    k.type = "number", k.default_value = real_text(v);
  } else if constexpr (std::is_same_v<T, std::string>) {
    k.type = "text", k.default_value = v.empty() ? "\"\"" : v;
  } else if constexpr (std::is_enum_v<T>) {
    k.type = enum_choices<T>(), k.default_value = enum_name(v);
  } else {
    static_assert(std::is_same_v<T, glm::vec3>);
    k.type = "3 numbers", k.default_value = "[" + real_text(v.x) + ", " + real_text(v.y) + ", " + real_text(v.z) + "]";
  }
  return k;
}

}  // namespace

std::vector<ConfigKeyInfo> config_keys() {
  std::vector<ConfigKeyInfo> keys;
  const TrainConfig defaults;
  visit_fields(defaults, [&](const char* name, const auto& v, Doc doc) {
    keys.push_back(key_info(name, v, doc));
  });
  return keys;
}

std::string train_options_reference() {
  const std::vector<ConfigKeyInfo> keys = config_keys();
  std::vector<std::string> sections;
  for (const ConfigKeyInfo& k : keys)
    if (!k.section.empty() && std::find(sections.begin(), sections.end(), k.section) == sections.end())
      sections.push_back(k.section);
  size_t user = 0;
  for (const ConfigKeyInfo& k : keys) user += !k.doc.empty();
  std::string md =
      "# Training options\n\n"
      "<!-- Generated by `goris config --reference > docs/reference/train-options.md` from the documentation "
      "beside each setting in train/config/train_config.cpp (visit_fields); edit it there. -->\n\n"
      "The " + std::to_string(user) + " settings of a training run a user is expected to touch, by their "
      "`config.json` key. Each is given as `goris train --set KEY=VALUE`, in a preset file "
      "(`resources/presets/`, `goris train --preset`) or in the editor with `set KEY VALUE`. A run's "
      "`config.json` holds all " + std::to_string(keys.size()) + " settings; `goris config --all` lists them "
      "with their defaults.\n";
  for (const std::string& s : sections) {
    md += "\n## " + s + "\n\n| key | default | type | meaning |\n|---|---|---|---|\n";
    for (const ConfigKeyInfo& k : keys) {
      if (k.section != s) continue;
      std::string doc = k.doc;
      for (size_t at = doc.find('|'); at != std::string::npos; at = doc.find('|', at + 2)) doc.replace(at, 1, "\\|");
      md += "| `" + k.key + "` | `" + k.default_value + "` | " + k.type + " | " + doc + " |\n";
    }
  }
  return md;
}

}  // namespace goris
