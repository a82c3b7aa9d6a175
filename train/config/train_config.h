#pragma once
// Everything that defines a training run (the numbers of docs/design/conventions.md and docs/design/maths.md
// as defaults). Stored as config.json in the run folder and inside every checkpoint, so a run can be resumed
// or repeated exactly.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "core/compute/device_choice.h"
#include "core/util/named_enum.h"
#include "train/optimizer/densify.h"

namespace goris {

// What training does on a non-finite loss or gradient (NanSettings::policy; `nan_policy` in config.json).
enum class NanPolicy { Recover, Stop };
template <>
struct EnumNames<NanPolicy> {
  static constexpr std::array<std::pair<NanPolicy, const char*>, 2> names{{{NanPolicy::Recover, "recover"}, {NanPolicy::Stop, "stop"}}};
};

// Which Gaussians emit into traced rays (IntrinsicSettings::emit; `intrinsic_emit` in config.json).
enum class EmitSource { Region, Mask, Max };
template <>
struct EnumNames<EmitSource> {
  static constexpr std::array<std::pair<EmitSource, const char*>, 3> names{
      {{EmitSource::Region, "region"}, {EmitSource::Mask, "mask"}, {EmitSource::Max, "max"}}};
};

// What a run trains (TrainConfig::mode; `mode` in config.json, `goris train --mode`).
enum class TrainMode { Radiance, Intrinsic, Auto };
template <>
struct EnumNames<TrainMode> {
  static constexpr std::array<std::pair<TrainMode, const char*>, 3> names{
      {{TrainMode::Radiance, "radiance"}, {TrainMode::Intrinsic, "intrinsic"}, {TrainMode::Auto, "auto"}}};
};

struct LearningRates {
  float position_init = 1.6e-4f;  // x scene extent, decays exponentially to position_final
  float position_final = 1.6e-6f;
  int position_max_steps = 0;  // decay length; 0 = the whole run (short schedules still anneal)
  // The SH colour's base rate (3DGS's) at the full 30K schedule. A shorter run multiplies it by
  // (30000 / iterations)^sh_dc_short_run_power, runs under 2000 iterations by a 2000-iteration run's factor
  // (TrainConfig::sh_dc_rate): Adam moves a parameter by about its rate per step, and at 2K iterations 3DGS's
  // rate leaves a random start's grey fog short of a bright floor that fills the views
  // (docs/design/deviations.md, The colour's rate in short runs). 0 = the fixed rate.
  float sh_dc = 2.5e-3f;
  float sh_dc_short_run_power = 0.5f;
  float sh_rest = 2.5e-3f / 20.0f;  // 1.25e-4
  float opacity = 0.05f;
  float scale = 5e-3f;
  float rotation = 1e-3f;
  // F0, roughness, diffuse. 4x the SH colour's rate of a full run: at 2K-4K iterations the colour's rate left
  // steel at roughness ~0.5 and the table's look in D (docs/design/deviations.md, Learning rates of the
  // materials).
  float materials = 0.01f;
  float region = 5e-3f;
  float label = 0.01f;
};

// Stage 1 in intrinsic mode (docs/design/maths.md; paper S1.5). Iteration numbers are those of a full 30K
// schedule; shorter runs scale them by iterations / 30000 (see TrainConfig::scaled_iteration), except the
// warm-up: a short run keeps warmup_min_fraction of itself in radiance mode (TrainConfig::shading_from), and the
// shading phase's own schedule points follow it (TrainConfig::shading_phase_iteration).
struct IntrinsicSettings {
  int warmup = 4000;               // radiance-only iterations before shading with tracing starts
  // ... but at least this fraction of a shorter run (never longer than `warmup` itself). The paper's 13 %
  // leaves a 2K run 267 radiance iterations: too few for the geometry the shading needs
  // (docs/design/deviations.md, The warm-up of short runs).
  float warmup_min_fraction = 0.5f;
  int env_resolution = 64;         // cube map face size (paper 256; 64 suffices at the data sets' 256 px)
  float env_initial = 0.5f;        // initial radiance of every texel
  // Where the environment lies (render/envmap/env_proxy_math.h). env_distance > 0: on a sphere around the
  // point the training cameras look at, of radius env_distance x their mean distance to it; the trainer
  // resolves it into env_center / env_radius (world units), which the run's config keeps, so every later
  // render reads the same sphere. 0 (the paper): at infinity. Default 1, for bounded captures (an object on a
  // table in a room), with emit = mask and the repeated prune (docs/design/deviations.md, The environment on
  // a sphere); set 0 for an outdoor capture whose light is at infinity. With the table's normals held flat
  // (glossy_plane_align) 1.4 places the area light's reflection (docs/design/deviations.md, The glossy
  // surface held to its plane).
  float env_distance = 1.0f;
  glm::vec3 env_center{0.0f};
  float env_radius = 0.0f;
  float init_roughness = 0.5f;     // every Gaussian's roughness and F0 at the start (the paper's 0.5)
  float init_fresnel = 0.5f;
  float lr_env = 0.03f;            // environment map: 0.03 -> 0.003 exponentially over the shading phase
  float lr_env_final = 0.003f;
  float lr_net = 1e-5f;            // roughness net, eased in between warmup and net_ease_until
  int net_ease_until = 10000;
  bool screen_space_filter = true; // L_ind and V through the screen-space glossy filter (+ssf)
  int net_hidden_layers = 6;       // 3x3 layers of the roughness net
  float ray_offset = 0.0f;         // world units; 0 = 0.02 x scene extent (ShadingSettings::default_ray_offset)
  // > 0: Gaussians whose emit weight is below this are transparent to the reflection rays (neither occlude
  // nor emit). A ray reflected off a plane never meets that plane again, but it starts inside the glossy
  // surface's own Gaussians, which the ray offset only partly skips and which then dim L_ind and V; skipping
  // them lets the offset be small, so that an object's foot is reflected too. For planar glossy surfaces
  // (with glossy_plane); a curved glossy object would stop shadowing itself. 0 = off (the paper).
  float trace_glossy_transparent = 0.0f;
  bool divide_opaque = true;       // the authors' L = colour / alpha on opaque rays
  // > 0: at the last warm-up iteration remove the Gaussians seen only behind glossy surfaces (the warm-up's
  // mirror world, train/loop/mirror_world.h); the value is the depth tolerance (x the rendered depth). Part
  // of the default stage-1 setting (emit = mask, this, repeat, env_distance 1; docs/design/deviations.md, The
  // warm-up's mirror world is pruned). With it the removal needs the twin plane fitted to the flat Gaussians
  // (core/scene/mirror_twins.h): fitted by distance, the plane missed the mirror twin.
  float prune_mirror_world = 0.05f;
  // With prune_mirror_world on: prune again after every densification of the shading phase, so the mirror
  // world cannot grow back while the glossy term learns to carry the reflections.
  bool prune_mirror_world_repeat = true;
  // From the last warm-up iteration on, keep the Gaussians over glossy pixels on the cameras' side of the
  // glossy plane (train/loop/glossy_plane.h). For planar glossy surfaces; off until measured.
  bool glossy_plane = false;
  // With glossy_plane: remove the Gaussians it had to put back, at its next refresh (glossy_plane.h).
  bool glossy_plane_prune_sinkers = false;
  // With glossy_plane: turn the flat Gaussians in the plane so that their normal is the plane's (glossy_plane.h).
  // Needs the environment's sphere where the light is (env_distance 1.4 with trace_glossy_transparent; at 1
  // it misplaces the light's reflection); off by default (docs/design/deviations.md, The glossy surface held
  // to its plane).
  bool glossy_plane_align = false;
  // Coarse tracing (train/intrinsic/coarse_tracing.h): with the filter on, one reflection ray per aligned
  // 2^k x 2^k block of glossy pixels whose blur level is k or coarser (k <= coarse_max_level).
  bool coarse_tracing = false;
  int coarse_max_level = 2;
  // Loss weights (0 = off).
  float normal_prior = 0.5f;       // decays to normal_prior_final between warmup and normal_prior_until
  float normal_prior_final = 0.001f;
  int normal_prior_until = 10000;
  float smoothness = 0.05f;        // edge-aware smoothness of F0, roughness and the normal on the glossy mask
  // Whether the region losses and the smoothness also run in the radiance warm-up (the paper applies every
  // loss from iteration 1). On the half-transparent warm-up geometry they drive F0 and roughness to ~0
  // before any shading can say otherwise; starting them with the shading did not gain on the mean alone
  // (docs/design/deviations.md, Material losses in the warm-up).
  bool material_losses_in_warmup = true;
  float region = 1.0f;             // mean(M_gt M)
  float label = 1.0f;              // BCE of the rendered label against the object masks
  // Which Gaussians emit into traced rays: region (the paper: the learned region weight M) or mask
  // (1 - the Gaussian's mean glossy-mask value over the training views its centre projects into, refreshed
  // every 25 iterations; needs glossy masks) or max (the larger of the two; M keeps its tracer gradient
  // where it is the larger). Renders of a trained run recompute mask weights from the same masks
  // (load_run_renderer), so eval, render, export and the removal see the model that was trained. Default
  // mask, with the prune and the sphere above (docs/design/deviations.md, Emission from the glossy masks).
  EmitSource emit = EmitSource::Mask;
  std::string normals;             // folder of normal-prior maps (empty = none); see train/run/normal_prior.h
  // --mode auto (train/setup/auto_mode.h). With glossy masks: intrinsic when at least auto_mask_fraction
  // of their pixels are glossy. Without: glossy regions detected by multi-view photo-consistency
  // (train/setup/glossy_detection.h): a pixel is glossy when its colour lies more than detect_threshold
  // (mean over RGB) outside what the detect_neighbours nearest views show around the same surface point,
  // and the scene is when detect_fraction of the covered pixels are. Tuned on the GOR-IS-style data sets at
  // 128 px (docs/design/maths.md, Glossy detection).
  float auto_mask_fraction = 0.005f;
  int detect_neighbours = 2;
  float detect_threshold = 0.03f;
  float detect_depth_tolerance = 0.03f;  // relative depth difference of "the same surface point"
  int detect_search_radius = 1;          // pixels: colour range of this window (geometry errors)
  int detect_depth_window = 2;           // pixels: search the depths the model shows this near (0 = off)
  int detect_morph_radius = 1;           // opening/closing of the detections (thin geometric-error lines)
  float detect_fraction = 0.0008f;
  int detect_width = 128;                // detection at this image width at most (0 = training size)
  int detect_after = 4000;               // iterations (not scaled) before detecting, at most half the run
  int detect_settled = 4000;             // ... but never before this many (not scaled; train/setup/auto_mode.h)
  float detect_plane_tolerance = 0.05f;  // masks grown over the detections' plane(s), x camera distance (0 = off)
  bool detect_mirror_world = true;       // also glossy when the model holds a mirror world (train/setup/mirror_world_detection.h)
};

// The training data and what of it a run uses (TrainConfig::input; config.json keys as the fields' names).
struct InputSettings {
  std::string data;             // data set path (as given, made absolute)
  // What the run was trained on, recorded when training starts (train/run/run_data.h): the training views'
  // count and a hash of their names and image sizes, so that a moved data set given with --data is checked
  // to be the same one. Empty in runs that predate the record.
  std::string data_views;
  float downscale = 1.0f;       // --downscale
  int resolution = 0;           // --resolution: target width in pixels (0 = use downscale)
  glm::vec3 background{0.0f};   // RGBA images composited on it; also the renderer's background
  // What of the data set to use (the stability bench's failure cases): the glossy masks (--mode auto then
  // detects glossy regions itself), the object masks, and at most this many training views (0 = all; a
  // subset is spread evenly over the views in file order).
  bool use_glossy_masks = true;
  bool use_object_masks = true;
  int max_train_views = 0;
  // Glossy masks read from this folder (gloss_<view name>.png at the training size) instead of the data
  // set's: where --mode auto keeps the masks it detected (RUN/detected_gloss). Empty = the data set's.
  std::string glossy_mask_dir;
  // Set by --mode auto when the data have no glossy masks: the run trains radiance through the warm-up,
  // then detects glossy regions and switches to intrinsic (mode "intrinsic", glossy_mask_dir = the
  // detected masks) or stays radiance; the decision clears it, so a resumed run never detects twice.
  bool auto_detect_glossy = false;
};

// The largest random initialisation a configuration accepts: beyond it the points alone outgrow a
// workstation's memory (each is a Gaussian with its optimiser state).
constexpr int kMaxRandomInitPoints = 20000000;

// The model training starts from (TrainConfig::init; config.json keys random_init_points,
// random_init_box_ratio and init_model).
struct InitSettings {
  // When the data set has no SfM points: random points in a box around the cameras' focus.
  int random_points = 100000;  // at most kMaxRandomInitPoints
  float random_box_ratio = 0.33f;
  // A model file to start from instead (`goris train --init`: 3DGS PLY, compressed PLY, SPZ, .splat or GLB,
  // core/io/splat_formats.h), in the data set's world frame: say, a scene made by another tool, refined here,
  // or trained further in intrinsic mode. Its Gaussians start as they are (materials at the intrinsic start
  // values unless the file has them); the SH degree grows from 0 as for any start. "" = SfM or random points.
  std::string model;
};

// The loss terms every mode trains with (the intrinsic mode's own are in IntrinsicSettings;
// TrainConfig::loss; config.json keys as the fields' names).
struct LossSettings {
  float lambda_ssim = 0.2f;            // colour loss (1 - l) L1 + l (1 - SSIM)
  // L1 between the rendered alpha and the images' alpha channel (views without one are skipped). Over a
  // black background a dark surface can be half transparent and still match the colour; steel_snowman's
  // table was (alpha 0.3-0.7 after the warm-up), which lets a mirror world show through it. 0 = off.
  float alpha_weight = 0.0f;
  float depth_normal_weight = 0.05f;   // RaDe-GS depth-normal consistency ...
  // ... from this iteration (0 weight = off). Deliberately NOT scaled with the run length like the other
  // schedule points: runs shorter than 7K never use it. Scaled into a short run, or started with the
  // shading, it cost both modes on the glossy scenes (docs/design/deviations.md, Depth-normal consistency
  // from an absolute iteration).
  int depth_normal_from = 7000;
  // Depth distortion (2DGS; the paper's stage 1 at 1000 for bounded scenes, on after 3K of 30K iterations,
  // here scaled to the run's length): train/losses/depth_distortion.h. 0 = off.
  float depth_distortion_weight = 0.0f;
  int depth_distortion_from = 3000;
  int depth_distortion_until = 0;  // last iteration with the distortion (of the full schedule, scaled); 0 = to the end
  // The distortion's weight on glossy-mask pixels relative to the rest (1 = the paper). Behind a planar
  // mirror a radiance field needs a second, virtual surface (the mirror world) until the traced term
  // carries the reflection; at 0 the loss leaves those pixels alone (docs/design/deviations.md, Depth
  // distortion off by default).
  float depth_distortion_glossy = 1.0f;
  float depth_normal_median_ratio = 0.6f;  // blend of the median- and expected-depth normals (RaDe-GS)
};

// The degree of the colour's spherical harmonics (TrainConfig::sh; config.json keys sh_degree_interval and
// max_sh_degree).
struct ShSettings {
  int degree_interval = 1000;  // SH degree +1 every this many iterations
  int max_degree = 3;
};

// Mip-Splatting's filters (TrainConfig::anti_aliasing; config.json keys as the fields' names).
struct AntiAliasingSettings {
  bool filter_3d = true;               // Mip-Splatting 3D filter
  int filter_3d_interval = 100;        // recomputed this often after densification ends
  bool filter_2d = true;               // Mip-Splatting 2D filter (else the 3DGS 0.3 px dilation)
};

// Stage-2 fine-tune (views with InpaintTargets): appearance loss (L1 + SSIM instead of the paper's LPIPS,
// which needs network weights) on the rough part of the hole, material L1 on the glossy part
// (TrainConfig::inpaint; `inpaint_<field>` in config.json).
struct InpaintWeights {
  float appearance_weight = 1.0f;
  float material_weight = 1.0f;
};

// Non-finite losses or gradients (TrainConfig::nan; `nan_<field>` in config.json): recover skips the step and
// multiplies every learning rate by lr_factor (stopping after max_skips skipped steps in a row), stop stops
// at once. Either way the message names the iteration, the view, the loss term or parameter group;
// checkpoints stay intact.
struct NanSettings {
  NanPolicy policy = NanPolicy::Recover;
  float lr_factor = 0.5f;
  int max_skips = 10;
};

// What a run writes beside the model as it trains (TrainConfig::bookkeeping; config.json keys as the fields'
// names).
struct BookkeepingSettings {
  int log_interval = 100;         // log.csv line every this many iterations
  int checkpoint_interval = 2000; // 0 = only at the end / on interruption
  int keep_checkpoints = 2;       // older checkpoint files are deleted
};

struct TrainConfig {
  // Radiance: SH colour only (also the warm-up of intrinsic stage 1); Intrinsic: stage 1 with
  // materials, tracing and shading (the data set's glossy masks drive the region loss); Auto: intrinsic for
  // a glossy scene, radiance otherwise (train/setup/auto_mode.h), resolved before training starts, so a run's
  // config.json names the mode it trained in. The default: on the generalization suite it removes more of
  // the target's reflection than radiance on the mean and the worst glossy scene (docs/results).
  TrainMode mode = TrainMode::Auto;
  int iterations = 30000;
  std::uint64_t seed = 0;
  DeviceChoice device = DeviceChoice::Auto;

  // The settings by group, in the order of their keys in config.json (each group's fields are documented in
  // its struct; visit_fields in train_config.cpp maps the flat keys onto them).
  InputSettings input;
  InitSettings init;
  LearningRates lr;
  LossSettings loss;
  ShSettings sh;
  DensifySettings densify;
  AntiAliasingSettings anti_aliasing;
  IntrinsicSettings intrinsic;
  InpaintWeights inpaint;
  NanSettings nan;
  BookkeepingSettings bookkeeping;

  // An iteration number of the full 30K schedule scaled to this run's length (never above it as given).
  int scaled_iteration(int full_schedule_iteration) const;
  // The SH colour's base learning rate of this run: lr.sh_dc x (30000 / max(iterations, 2000))^
  // lr.sh_dc_short_run_power for runs shorter than 30000 iterations, lr.sh_dc otherwise.
  float sh_dc_rate() const;
  // Last iteration of adaptive density control: densify.until_iter, but at most densify.until_fraction of
  // the run, so that a shortened schedule ends with a stretch of pure optimisation instead of adding
  // untrained Gaussians at the very end.
  int densify_until() const;
  // The interval of opacity resets in this run: densify.opacity_reset_interval scaled by the run's window
  // (densify_until() / until_iter) when that is shorter than the full one, rounded to a whole number of
  // densification intervals (at least one).
  int opacity_reset_every() const;
  // The last radiance-only iteration of intrinsic mode: max(scaled warm-up, min(warm-up, min_fraction x run)).
  int shading_from() const;
  // Whether the mirror world is pruned after iteration `it` (1-based; `densified`: that iteration ran a
  // densification step): at the last warm-up iteration, and with prune_mirror_world_repeat after every
  // densification of the shading phase. Never with intrinsic.prune_mirror_world = 0.
  bool prunes_mirror_world_after(int it, bool densified) const;
  // Whether iteration `it` (1-based) trains with the depth distortion: after its scaled start, up to its scaled
  // end (loss.depth_distortion_until; 0 = to the end) and only with a positive weight.
  bool depth_distortion_at(int it) const;
  // A full-schedule iteration of the shading phase (>= the warm-up) mapped onto this run's shading phase,
  // [shading_from(), iterations]; earlier ones map to shading_from().
  int shading_phase_iteration(int full_schedule_iteration) const;

  // Throws goris::Error(what, problem) for a value outside its range.
  void validate(const std::string& what) const;
};

// config.json: every setting, and "config_version" (train/config/config_migration.h).
void to_json(nlohmann::json& j, const TrainConfig& c);
// Reads a config.json object of this or an older version (migrated first: renamed keys, dropped settings,
// keys older files lack; config_migration.h). Missing keys keep their defaults; unknown keys are errors
// (typos must not pass silently).
void from_json(const nlohmann::json& j, TrainConfig& c);
// `--set KEY=VALUE` overrides of config.json keys (VALUE as JSON: number, true/false, "string" or [1,2,3],
// else a plain string); goris::Error naming the setting for an unknown or removed key or a value that does
// not parse. `label` heads the messages: the CLI's "--set", the editor's "set", a preset's file.
void apply_config_overrides(const std::vector<std::string>& sets, TrainConfig& config,
                            const std::string& label = "--set");

// One config.json key as `goris config` and docs/reference/train-options.md show it.
struct ConfigKeyInfo {
  std::string key;
  std::string type;           // "true/false", "whole number", "number", "text" or "[r, g, b]"
  std::string default_value;  // as a person writes it: 0.0002, radiance, "" (empty text), [0, 0, 0]
  // User-facing settings (the few a user is expected to touch): the heading they are listed under and one
  // line of documentation. Empty for the rest, which config.json and --set accept all the same.
  std::string section, doc;
};
// Every config.json key, in config.json's definition order.
std::vector<ConfigKeyInfo> config_keys();
// docs/reference/train-options.md: the user-facing settings by section, with their defaults (Markdown).
std::string train_options_reference();

}  // namespace goris
