#include "removal/pipeline/removal_pipeline.h"
#include "removal/pipeline/removal_ablations.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/io/json_file.h"
#include "core/io/made_from.h"
#include "core/inpaint/harmonic_inpainter.h"
#include "core/inpaint/inpainter.h"
#include "core/io/dataset.h"
#include "core/io/file_bytes.h"
#include "core/io/image.h"
#include "core/io/output_path.h"
#include "core/io/ply.h"
#include "core/scene/mirror_twins.h"
#include "core/inpaint/region_fill.h"
#include "removal/masks/planar_reflection.h"
#include "removal/selection/selection_file.h"
#include "removal/pipeline/removal_selection.h"
#include "removal/selection/selection_labels.h"
#include "core/scene/selection_points.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "train/loop/trainer.h"
#include "core/compute/bench.h"
#include "core/util/error.h"
#include "core/util/fnv1a.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "render/raster/rasterizer.h"
#include "removal/lift/dereflect.h"
#include "removal/lift/photo_under_reflection.h"
#include "removal/lift/finetune_views.h"
#include "removal/masks/inpaint_mask.h"
#include "removal/masks/inpaint_mask_scene.h"
#include "removal/lift/inpainted_maps.h"
#include "removal/lift/lift.h"
#include "removal/masks/lighting_aware_mask.h"
#include "removal/lift/plane_depth.h"
#include "removal/lift/surface_detail.h"
#include "removal/lift/reference_views.h"
#include "removal/masks/removed_glossy_masks.h"
#include "removal/shadow/target_shadow_scene.h"
#include "train/setup/auto_mode.h"
#include "train/radiance/raster_renderer.h"
#include "train/setup/run_renderer.h"
#include "train/setup/training_setup.h"

namespace goris {

namespace fs = std::filesystem;

const char* removal_step_name(RemovalStep s) {
  static const char* names[kRemovalStepCount] = {"selection",       "lighting masks", "inpaint masks", "reference views",
                                                 "2D inpainting", "3D lift",        "fine-tune"};
  return names[int(s)];
}

namespace {

using Clock = std::chrono::steady_clock;

struct StepScope {
  RemovalReport& report;
  RemovalStep step;
  const std::function<void(const RemovalProgress&)>& cb;
  Clock::time_point t0 = Clock::now();
  StepScope(RemovalReport& r, RemovalStep s, const std::function<void(const RemovalProgress&)>& c)
      : report(r), step(s), cb(c) {
    tell(0, 1, "");
  }
  void tell(std::size_t done, std::size_t total, const std::string& detail) const {
    if (cb) cb({step, done, std::max<std::size_t>(total, 1), detail});
  }
  // Marks the step complete (100 %) and records its time.
  void finish(const std::string& detail = "") {
    report.seconds[int(step)] += std::chrono::duration<double>(Clock::now() - t0).count();
    tell(1, 1, detail);
  }
};

std::string step_error(RemovalStep s, const std::string& problem) {
  return std::string("goris remove (") + removal_step_name(s) + "): " + problem;
}

Mask mask_from_values(const std::vector<float>& v, int w, int h, float threshold) {
  Mask m(w, h);
  for (std::size_t p = 0; p < v.size(); ++p) m.data[p] = v[p] > threshold ? 255 : 0;
  return m;
}

bool any_glossy_mask(const std::vector<TrainView>& views) {
  return std::any_of(views.begin(), views.end(), [](const TrainView& v) { return !v.glossy_mask.empty(); });
}

// E_obj of the lighting-aware mask (in [0, 1]) as a grey image, for a person to see what tau cut.
Image energy_image(const std::vector<float>& e, const Camera& camera) {
  Image im(camera.width, camera.height, 1, Device::CPU);
  for (std::size_t p = 0; p < e.size() && p < im.pixel_count(); ++p) im.pixels[p] = std::clamp(e[p], 0.0f, 1.0f);
  return im;
}

// Stage 2's training configuration from stage 1's.
TrainConfig finetune_config(const TrainConfig& s1, int iterations) {
  TrainConfig c = s1;
  c.iterations = iterations;
  c.densify.from_iter = 1 << 30;  // the lift placed the new Gaussians; no density control
  c.densify.until_iter = 0;
  c.densify.opacity_reset_interval = 1 << 30;
  c.lr.position_init = s1.lr.position_final * 10;  // late-stage learning rates: refine, do not rebuild
  c.lr.position_final = s1.lr.position_final;
  c.lr.label = 0;  // labels are frozen: the target is gone
  c.intrinsic.warmup = 0;
  c.intrinsic.lr_env = c.intrinsic.lr_env_final = c.intrinsic.lr_net = 0;  // environment and net frozen
  c.intrinsic.smoothness = 0;  // the paper drops smoothness and the label BCE in stage 2
  c.intrinsic.label = 0;
  c.intrinsic.normal_prior = c.intrinsic.normal_prior_final;
  c.loss.depth_normal_from = s1.iterations > s1.loss.depth_normal_from ? 0 : 1 << 30;
  c.bookkeeping.checkpoint_interval = std::max(100, iterations / 4);
  c.bookkeeping.log_interval = std::max(10, std::min(100, iterations / 20));
  return c;
}

nlohmann::json options_json(const RemovalOptions& o) {
  nlohmann::json j;
  j["inpainter"] = o.inpainter;
  j["ablate"] = std::vector<std::string>(o.ablate.begin(), o.ablate.end());
  j["label_threshold"] = o.label_threshold;
  j["lighting_tau"] = o.lighting_tau;
  j["lighting_fresnel"] = o.lighting_relative_fresnel ? "relative" : "absolute";
  j["lighting_targets"] = o.dereflect_lighting ? "dereflect" : "exclude";
  j["view_fill_weight"] = o.view_fill_weight;
  j["photo_under_reflection"] = {o.photo_under_reflection.texture_multiple, o.photo_under_reflection.silhouette_margin};
  if (!o.fill_truth.empty()) j["fill_truth"] = fs::absolute(o.fill_truth).lexically_normal().string();
  return j;
}

// The selection as 16 hex digits (FNV-1a of the per-Gaussian mask): any added or dropped Gaussian changes it.
std::string selection_fingerprint(const SelectionMask& mask) {
  return hex16(fnv1a(std::string_view(reinterpret_cast<const char*>(mask.data()), mask.size())));
}

// Removes a fine-tune's checkpoints and results that were made from other inputs, so that neither a rerun
// nor render / eval of RUN/removal can pick them up.
void remove_stale_finetune(const fs::path& out) {
  std::error_code ec;
  fs::remove_all(out / "checkpoints", ec);
  // densify_stop.json: the record of a removed setting that older versions wrote.
  for (const char* f : {"point_cloud.ply", "report.json", "log.csv", "densify_stop.json", "config.json"})
    fs::remove(out / f, ec);
}

}  // namespace

RemovalReport run_removal(const fs::path& run_dir_in, const RemovalOptions& o,
                          const std::function<void(const RemovalProgress&)>& on_progress, const std::atomic<bool>* stop) {
  if (const std::string problem = ablation_problem(o.ablate); !problem.empty())
    throw Error(step_error(RemovalStep::Selection, problem));
  const fs::path run_dir = fs::absolute(run_dir_in);
  const TrainConfig config = read_run_config_with_data(run_dir, o.data);
  const Device device = resolve_device(o.device);
  const DatasetOptions dopt = dataset_options(config);
  Dataset ds = load_dataset(config.input.data, dopt);
  if (ds.train.empty()) throw Error(config.input.data, "the data set has no training views");
  select_training_data(config, ds);  // stage 2 sees the views and masks stage 1 trained with
  const float extent = scene_extent(ds);
  const std::vector<Camera> cameras = cameras_of(ds.train);
  const bool intrinsic = config.mode == TrainMode::Intrinsic;
  const bool materials = intrinsic && !o.ablate.count("material");

  RemovalReport report;
  const fs::path out = run_dir / "removal";
  report.out_dir = out;
  const RemoveIfLeftEmpty created(out);  // a removal refused below leaves no empty removal/ behind
  fs::create_directories(out);
  // Temporary files of a removal killed mid-write (masks, maps, checkpoints) go, in every folder of it.
  remove_stale_temp_files(out);
  std::error_code walk;
  for (const auto& e : fs::recursive_directory_iterator(out, walk))
    if (e.is_directory()) remove_stale_temp_files(e.path());
  std::string model_source;
  GaussianModel model = load_run_model(run_dir, device, &model_source);
  report.gaussians_before = model.count();
  // What the later steps' stored outputs are made from (made_from.h): stage 1's model and the options here,
  // the selection once step 1 has made it. The 2D-inpainting cache and the fine-tune reuse their outputs
  // only when their record matches.
  nlohmann::json made_from;
  made_from["stage1"] = {{"source", fs::path(model_source).lexically_relative(run_dir).generic_string()},
                         {"model", model_fingerprint(model)}};
  made_from["options"] = options_json(o);
  const RasterSettings raster = RasterRenderer::settings_for(config);
  auto cancelled = [&] { return stop && stop->load(); };
  // The training photos: the lighting step dereflects and relights them, the fine-tune trains on them.
  std::vector<TrainView> views = load_train_views(ds.train, dopt);
  std::vector<std::vector<float>> fill_truth;  // RemovalOptions::fill_truth, read before any work is done
  for (std::size_t i = 0; i < ds.train.size() && !o.fill_truth.empty(); ++i) {
    View tv = ds.train[i];
    tv.image = fs::path(o.fill_truth) / (tv.name + ".png");
    if (!fs::is_regular_file(tv.image))
      throw Error(tv.image.string(), "missing: --fill-truth needs every training view rendered without the target "
                                     "(goris synth --train-after DATA)");
    fill_truth.push_back(to_planar_rgb(load_view_image(tv, dopt, Device::CPU)));
  }
  std::vector<std::vector<float>> photos_as_taken;  // with fill_truth: before the lighting step changes them
  if (!fill_truth.empty())
    for (const TrainView& v : views) photos_as_taken.push_back(v.image);
  if (!config.input.glossy_mask_dir.empty())  // --mode auto's
    load_glossy_mask_folder(config.input.glossy_mask_dir, views);
  const bool glossy_masks = any_glossy_mask(views);

  // 1. Selection (removal_selection.h).
  const RemovalSelection sel = [&] {
    StepScope s(report, RemovalStep::Selection, on_progress);
    RemovalSelection r = select_for_removal(run_dir, model, o, intrinsic, glossy_masks, cameras, views);
    report.selected = count_selected(r.selected);
    report.mirror_twins = r.mirror_twins;
    report.underside = r.underside;
    report.glossy_plane = r.glossy_plane;
    r.record.model_fingerprint = model_fingerprint(model);
    write_selection(out / "selection.json", r.record, r.selected);
    made_from["selection"] = {{"gaussians", report.selected}, {"fingerprint", selection_fingerprint(r.selected)}};
    apply_selection_to_labels(model, r.selected);
    s.finish(std::to_string(report.selected) + " of " + std::to_string(model.count()) + " Gaussians" + r.note);
    return r;
  }();
  const SelectionMask& selected = sel.selected;
  const SelectionMask& target_only = sel.target;
  const MirrorPlane& glossy_plane = sel.glossy_plane;

  // The scene without the target (and twin): the dereflection's and the inpainting's renders, the lift's base.
  SplitScene split = split_removed(model, selected);
  ShadowRelight relit;

  // 2. Lighting-aware masks.
  std::vector<Mask> lighting(cameras.size()), reflection(cameras.size());
  std::optional<EnvironmentImage> environment;  // an intrinsic model's, for the shadow's light
  {
    StepScope s(report, RemovalStep::LightingMasks, on_progress);
    if (intrinsic && !o.ablate.count("lamask")) {
      const auto renderer = load_run_renderer(run_dir, config, extent, device);
      IntrinsicRenderer* ir = as_intrinsic(renderer.get());
      environment = EnvironmentImage{ir->environment().equirect_image(256), 256, glm::dvec3(config.intrinsic.env_center),
                                     double(config.intrinsic.env_radius)};
      fs::create_directories(out / "lighting_masks");
      fs::create_directories(out / "lighting_energy");
      if (o.lighting_relative_fresnel) report.lighting_fresnel_reference = glossy_fresnel_reference(model, selected);
      // The mirror twin, seen through the glossy surface, is the target's reflection too: its rasterized
      // coverage joins E_obj.
      std::optional<GaussianModel> twin_model;
      if (report.mirror_twins > 0) {
        twin_model.emplace(model.copy_to(model.device()));
        apply_selection_to_labels(*twin_model, sel.twins);
      }
      for (std::size_t i = 0; i < cameras.size(); ++i) {
        if (cancelled()) break;
        s.tell(i, cameras.size(), ds.train[i].name);
        std::vector<float> e = ir->reflected_label(model.view(true), cameras[i], report.lighting_fresnel_reference);
        if (twin_model) {
          const RasterOutput r = rasterize(twin_model->view(true), cameras[i], raster, twin_model->device());
          const std::vector<float> ex = r.gbuffer.extras.to_host();
          const std::size_t hw = e.size();
          for (std::size_t p = 0; p < hw && (extra::kLabel + 1) * hw <= ex.size(); ++p)
            e[p] = std::max(e[p], std::clamp(ex[std::size_t(extra::kLabel) * hw + p], 0.0f, 1.0f));
        }
        lighting[i] = lighting_aware_mask(e, cameras[i].width, cameras[i].height, {o.lighting_tau, -1});
        report.lighting_pixels += count_set(lighting[i]);
        save_mask_png(out / "lighting_masks" / (ds.train[i].name + ".png"), lighting[i]);
        save_png(out / "lighting_energy" / (ds.train[i].name + ".png"), energy_image(e, cameras[i]));
      }
      if (o.dereflect_lighting && !cancelled()) {  // dereflect.h: why the mask keeps a target
        const DereflectResult d = dereflect_views(
            *ir, model, split.kept, lighting, views, out / "dereflected",
            [&](std::size_t i, std::size_t n) { s.tell(i, n, "dereflecting " + ds.train[i].name); }, cancelled);
        report.dereflected_pixels = d.pixels;
      }
    }
    std::string shadow_note;
    if (!o.ablate.count("lamask") && !o.ablate.count("shadows") && !cancelled()) {
      s.tell(cameras.size(), cameras.size(), "the target's shadow");
      relit = relight_target_shadow(model, target_only, sel.shadow_excluded, glossy_plane.found ? &glossy_plane : nullptr, views,
                                    raster, out / "shadow", intrinsic ? ShadowSampleColour::Model : ShadowSampleColour::Photos,
                                    environment ? &*environment : nullptr);
      report.shadow_found = relit.fit.found;
      report.shadow = relit.fit.reason;
      report.shadow_pixels = relit.relit_pixels;
      shadow_note = relit.fit.found ? "; shadow: " + std::to_string(relit.relit_pixels) + " pixels relit (" +
                                          relit.fit.reason + ")"
                                    : "; no shadow: " + relit.fit.reason;
    }
    char f[64];
    std::snprintf(f, sizeof f, " (F relative to %.3f)", report.lighting_fresnel_reference);
    const std::string dereflect_note =
        report.dereflected_pixels ? "; " + std::to_string(report.dereflected_pixels) + " dereflected" : "";
    s.finish(std::to_string(report.lighting_pixels) + " pixels" +
             (o.lighting_relative_fresnel && intrinsic && !o.ablate.count("lamask") ? f : "") + dereflect_note +
             shadow_note);
  }
  if (cancelled()) return report.cancelled = true, report;

  // 3. Inpainting masks.
  std::vector<InpaintMaskView> holes;
  {
    StepScope s(report, RemovalStep::InpaintMasks, on_progress);
    InpaintMaskSettings ms;
    ms.raster = raster;
    holes = compute_inpaint_masks(model, selected, cameras, ms,
                                  [&](std::size_t i, std::size_t n) { s.tell(i, n, i < ds.train.size() ? ds.train[i].name : ""); });
    // The target mirrored through the glossy plane, on the glossy surface: its reflection, whatever the
    // model made of it (planar_reflection.h). Inpainted and kept out of the photo loss below. The surface is
    // that of the scene without the target (removed_glossy_masks.h): where the target stood in front of the
    // surface, the photo's mask says "not glossy", yet after the removal the surface and the reflection the
    // model keeps there (a radiance model's mirror twin) are seen.
    if (glossy_plane.found && glossy_masks && !o.ablate.count("lamask") && !o.ablate.count("reflection") &&
        !cancelled()) {
      GaussianModel mirrored = mirrored_through(model, target_only, glossy_plane);
      fs::create_directories(out / "reflection_masks");
      for (std::size_t i = 0; i < cameras.size(); ++i) {
        if (views[i].glossy_mask.empty()) continue;
        reflection[i] = planar_reflection_mask(mirrored, cameras[i], removed_glossy_mask(views[i], holes[i]), raster);
        report.reflection_pixels += count_set(reflection[i]);
        save_mask_png(out / "reflection_masks" / (ds.train[i].name + ".png"), reflection[i]);
      }
    }
    fs::create_directories(out / "inpaint_masks");
    for (std::size_t i = 0; i < holes.size(); ++i) {
      if (reflection[i].width == holes[i].mask.width) holes[i].mask = mask_or(holes[i].mask, reflection[i]);
      report.inpaint_pixels += count_set(holes[i].mask);
      save_mask_png(out / "inpaint_masks" / (ds.train[i].name + ".png"), holes[i].mask);
    }
    const std::string reflection_note =
        report.reflection_pixels ? " (" + std::to_string(report.reflection_pixels) + " in the planar reflection)" : "";
    s.finish(std::to_string(report.inpaint_pixels) + " pixels" + reflection_note);
  }

  // 4. Reference views.
  ReferenceChoice choice;
  {
    StepScope s(report, RemovalStep::ReferenceViews, on_progress);
    choice = choose_reference_views(holes, cameras);
    nlohmann::json j = nlohmann::json::array();
    for (std::size_t k = 0; k < choice.views.size(); ++k) {
      const int v = choice.views[k];
      report.reference_views.push_back(ds.train[std::size_t(v)].name);
      j.push_back({{"view", ds.train[std::size_t(v)].name},
                   {"mask_pixels", count_set(holes[std::size_t(v)].mask)},
                   {"angle_threshold_deg", choice.angle_threshold[k]}});
    }
    write_json_file(out / "reference.json", j);
    s.finish(std::to_string(choice.views.size()) + " views");
  }

  // 5. 2D inpainting (cached for resuming): the reference views, then (view_fill_weight > 0) every other view
  // with a hole.
  std::vector<std::size_t> fill_views;  // in the order of `inpainted` after the reference views
  if (o.view_fill_weight > 0) {
    std::vector<bool> is_reference(cameras.size(), false);
    for (int v : choice.views) is_reference[std::size_t(v)] = true;
    for (std::size_t v = 0; v < cameras.size(); ++v)
      if (!is_reference[v] && count_set(holes[v].mask) > 0) fill_views.push_back(v);
  }
  std::vector<MapSet> inpainted(choice.views.size() + fill_views.size());
  // surface_detail.h: a textured glossy surface trusts its smooth material fill less. Measured on the reference
  // views' removed maps where step 5 renders them, against the glossy masks the fine-tune will train with
  // (filled under the target, step 7); a cached step 5 leaves them for step 7 to render.
  const bool glossfill = intrinsic && !o.ablate.count("glossfill");
  std::vector<std::optional<double>> reference_detail(choice.views.size());
  std::vector<bool> reference_detail_measured(choice.views.size(), false);
  // The removed scene's maps of view v as the fills see them: rendered without the target, its shadow relit.
  auto removed_maps = [&](std::size_t v) {
    MapSet maps = render_removed_maps(split.kept, cameras[v], raster);
    if (relit.fit.found) relight_image(maps.rgb, relit.pixels[v], relit.s[v], relit.fit);  // the shadow is gone
    return maps;
  };
  // filled: removed_glossy_mask() of the view when the caller has it already.
  auto measure_detail = [&](std::size_t k, const Image& removed_rgb, const std::vector<float>& filled) {
    const std::size_t v = std::size_t(choice.views[k]);
    if (views[v].glossy_mask.empty()) return;
    std::vector<float> own;
    const std::vector<float>* g = &views[v].glossy_mask;
    if (glossfill) g = !filled.empty() ? &filled : &(own = removed_glossy_mask(views[v], holes[v]));
    reference_detail[k] = surface_detail_rms(removed_rgb, *g, holes[v].mask, o.surface_detail);
    reference_detail_measured[k] = true;
  };
  {
    StepScope s(report, RemovalStep::Inpaint2D, on_progress);
    const fs::path dir = out / "inpainted";
    fs::create_directories(dir);
    nlohmann::json opts = made_from;
    opts["materials"] = materials;
    const bool surface_fill = glossy_masks && !o.ablate.count("lamask") && !o.ablate.count("reflection");
    const bool lift_on_plane = surface_fill && glossy_plane.found;
    if (lift_on_plane)
      opts["lift_not_in_front_of"] = {glossy_plane.normal.x, glossy_plane.normal.y, glossy_plane.normal.z,
                                      glossy_plane.offset};
    opts["views"] = report.reference_views;
    // inpainted[k]: the reference views, then the other views' fills, kept apart from the reference views'
    // maps (the lift's input) under their own file stem.
    auto view_of = [&](std::size_t k) {
      return k < choice.views.size() ? std::size_t(choice.views[k]) : fill_views[k - choice.views.size()];
    };
    std::vector<std::string> stems;
    for (std::size_t k = 0; k < inpainted.size(); ++k)
      stems.push_back(ds.train[view_of(k)].name + (k < choice.views.size() ? "" : "_fill"));
    opts["fills"] = std::vector<std::string>(stems.begin() + std::ptrdiff_t(choice.views.size()), stems.end());
    const fs::path opts_path = dir / "made_from.json";
    // A record whose maps are not all there (removed by hand, or a folder copied in part) is no cache.
    const bool cached = made_from_changes(opts_path, opts).empty() &&
                        std::all_of(stems.begin(), stems.end(),
                                    [&](const std::string& stem) { return inpainted_maps_present(dir, stem); });
    std::unique_ptr<Inpainter> inp, fill_inp;
    const HarmonicInpainter harmonic;
    const bool own_depth = o.inpainter.rfind("cmd:", 0) != 0 && o.inpainter.rfind("dir:", 0) != 0;
    // The other views' fills are smooth targets for many views: with an external program or a folder of
    // ready-made maps (made for the reference views) they come from the default built-in inpainter.
    auto inpainter_for = [&](bool reference) -> const Inpainter& {
      if (reference || own_depth) return *inp;
      if (!fill_inp) fill_inp = make_inpainter(RemovalOptions{}.inpainter);
      return *fill_inp;
    };
    const std::size_t maps_per_view = materials ? 6 : 2;
    const std::size_t total = inpainted.size() * maps_per_view;
    std::size_t done = 0;
    struct Stopped {};  // a stop while the maps are filled leaves no record: a rerun fills them again
    try {
      for (std::size_t k = 0; k < inpainted.size(); ++k) {
        if (cancelled()) throw Stopped{};
        const bool reference = k < choice.views.size();
        const std::size_t v = view_of(k);
        const std::string& name = ds.train[v].name;
        const std::string& stem = stems[k];
        MapSet& m = inpainted[k];
        if (cached) {
          m = load_inpainted_maps(dir, stem);
          done += maps_per_view;
          s.tell(done, total, name + " (cached)");
          continue;
        }
        if (!inp) {
          // The cache is being rewritten: no map of an earlier run (other reference views) stays beside it.
          fs::remove_all(dir);
          fs::create_directories(dir);
          inp = make_inpainter(o.inpainter);
        }
        MapSet maps = removed_maps(v);
        std::vector<float> g = surface_fill ? removed_glossy_mask(views[v], holes[v]) : std::vector<float>();
        if (reference && materials) measure_detail(k, maps.rgb, g);
        maps.diffuse = Image();  // not used by the shading (D is the SH colour in rgb)
        if (!materials) {
          maps.normal = Image();
          maps.fresnel = Image();
          maps.roughness = Image();
          maps.region = Image();
        }
        if (!reference) maps.depth = Image();  // nothing is lifted from these views
        MapSetInpaintOptions mo;
        if (own_depth) mo.depth_inpainter = &harmonic;
        mo.on_map = [&](const std::string& map) {
          if (cancelled()) throw Stopped{};
          s.tell(done++, total, name + " " + map);
        };
        const Inpainter& fill_with = inpainter_for(reference);
        m = inpaint_map_set(fill_with, maps, holes[v].mask, name, mo);
        if (!reference) ++done;  // the depth map it skipped
        if (reference && lift_on_plane && !g.empty() && m.depth.channels == 1) {  // plane_depth.h: not into the air
          const Mask on_surface =
              mask_and(holes[v].mask, mask_from_values(g, cameras[v].width, cameras[v].height, 0.5f));
          report.lift_onto_plane_pixels += depth_onto_plane(m.depth, cameras[v], on_surface, glossy_plane);
        }
        if (surface_fill) {  // each side of the glossy surface's edge from its own side alone (region_fill.h)
          if (!g.empty()) {
            const MapInfo info{name, "rgb", MapKind::Color};
            m.rgb = refill_inside_region(fill_with, maps.rgb, m.rgb, holes[v].mask, g, info);
            for (float& x : g) x = 1.0f - x;
            m.rgb = refill_inside_region(fill_with, maps.rgb, m.rgb, holes[v].mask, g, info);
          }
        }
        save_inpainted_maps(dir, stem, m, /*previews=*/reference);
      }
    } catch (const Stopped&) {
      return report.cancelled = true, report;
    }
    if (!cached) {
      write_made_from(opts_path, opts);
    }
    s.finish(fill_views.empty() ? std::string()
                                : std::to_string(fill_views.size()) + " other views filled as targets");
  }

  // 6. 3D lift.
  LiftResult lift;
  GaussianModel lifted = split.kept.copy_to(device);
  {
    StepScope s(report, RemovalStep::Lift, on_progress);
    std::vector<LiftView> lv;
    for (std::size_t k = 0; k < choice.views.size(); ++k) {
      const std::size_t v = std::size_t(choice.views[k]);
      lv.push_back({int(v), cameras[v], &holes[v].mask, &inpainted[k]});
    }
    if (!lv.empty()) lift = lift_reference_views(lifted, lv);
    report.added = lift.added;
    s.finish(std::to_string(lift.added) + " Gaussians added" +
             (report.lift_onto_plane_pixels ? " (" + std::to_string(report.lift_onto_plane_pixels) +
                                                  " hole pixels moved back onto the glossy plane)"
                                            : std::string()));
  }

  // 7. Fine-tune.
  {
    StepScope s(report, RemovalStep::FineTune, on_progress);
    const int iters = o.finetune_iterations > 0 ? o.finetune_iterations
                                                : std::max(100, config.scaled_iteration(4000));
    TrainConfig ft = finetune_config(config, iters);
    if (glossfill) {  // removed_glossy_masks.h: no ghost where the target stood
      report.glossy_filled_pixels = fill_removed_glossy_masks(views, holes);
      // A glossy_mask_dir must hold every view's mask (load_glossy_mask_folder), so only a complete set is written.
      if (std::all_of(views.begin(), views.end(), [](const TrainView& v) { return !v.glossy_mask.empty(); })) {
        save_glossy_mask_folder(out / "glossy_masks", views);
        ft.input.glossy_mask_dir = (out / "glossy_masks").string();
      }
    }
    if (materials) {  // the measure of step 5 (a cached step 5: rendered here, the masks already filled)
      std::vector<std::optional<double>> detail;
      for (std::size_t k = 0; k < choice.views.size(); ++k) {
        const std::size_t v = std::size_t(choice.views[k]);
        const TrainView& tv = views[v];
        if (tv.glossy_mask.empty()) continue;
        if (!reference_detail_measured[k]) measure_detail(k, removed_maps(v).rgb, tv.glossy_mask);  // filled by now
        detail.push_back(reference_detail[k]);
      }
      if (const auto d = median_surface_detail(detail)) {
        report.surface_detail = *d;
        if (*d > o.surface_detail.textured_above) ft.inpaint.material_weight *= o.textured_material_weight;
      }
    }
    report.material_weight = ft.inpaint.material_weight;
    std::vector<Mask> exclude(views.size());
    std::vector<FinetuneViewInputs> inputs(views.size());
    std::vector<ReferenceTargets> refs;
    for (std::size_t k = 0; k < choice.views.size(); ++k) {
      const std::size_t v = std::size_t(choice.views[k]);
      inputs[v].reference = int(k);
      refs.push_back({&holes[v].mask, &inpainted[k]});
    }
    for (std::size_t k = 0; k < fill_views.size(); ++k) {
      const std::size_t v = fill_views[k];
      inputs[v].fill = int(refs.size());
      refs.push_back({&holes[v].mask, &inpainted[choice.views.size() + k], o.view_fill_weight});
    }
    for (std::size_t i = 0; i < views.size(); ++i) {
      const int w = cameras[i].width, h = cameras[i].height;
      // Object mask of the data set (when given) U what the selection covers (dilated: soft edges), and the
      // reflections only under the paper's rule (by default their photos were dereflected in step 2).
      Mask ex = dilate_mask(holes[i].covered, soft_edge_radius(w));
      if (!views[i].object_mask.empty()) ex = mask_or(ex, mask_from_values(views[i].object_mask, w, h, 0.5f));
      if (lighting[i].width == w && !o.dereflect_lighting) ex = mask_or(ex, lighting[i]);
      if (reflection[i].width == w) {
        // photo_under_reflection.h: on a textured surface the dereflected photo keeps its loss where it differs
        // from the view's fill (a reference view's or its own) only by the texture.
        const int f = inputs[i].reference >= 0 ? inputs[i].reference : inputs[i].fill;
        std::size_t kept = 0;
        const bool keep = o.dereflect_lighting && lighting[i].width == w && f >= 0 && !o.ablate.count("texture");
        ex = mask_or(ex, keep ? reflection_left_to_the_fill(reflection[i], lighting[i], ex, views[i].image,
                                                            refs[std::size_t(f)].maps->rgb, report.surface_detail,
                                                            o.photo_under_reflection, &kept)
                              : reflection[i]);
        report.reflection_photo_pixels += kept;
      }
      exclude[i] = std::move(ex);
      inputs[i].exclude = &exclude[i];
      inputs[i].removed_depth = &holes[i].removed_depth;
    }
    const FinetuneViewStats fs_stats = prepare_finetune_views(views, inputs, refs, lift.points);
    if (!o.fill_truth.empty()) {
      report.truth_error = photo_targets_against_truth(views, photos_as_taken, fill_truth);
      report.fill_truth_pixels = use_true_fills(views, fill_truth);
    }

    TrainerState state;
    auto renderer = make_renderer(ft, extent, device);
    // A checkpoint is resumed only when it was made from the same inputs; otherwise it and its results go
    // and the fine-tune starts over, saying what changed.
    nlohmann::json finetune_from = made_from;
    finetune_from["materials"] = materials;
    finetune_from["iterations"] = iters;
    finetune_from["material_weight"] = ft.inpaint.material_weight;
    const fs::path record = out / "made_from.json";
    auto resume = latest_checkpoint(out);
    const bool earlier = resume || fs::exists(run_ply_path(out)) || fs::exists(out / "report.json");
    if (const std::string changes = made_from_changes(record, finetune_from); earlier && !changes.empty()) {
      report.finetune_restarted = changes;
      s.tell(0, std::size_t(iters), "starting over: the earlier fine-tune was made from other inputs (" + changes + ")");
      remove_stale_finetune(out);
      resume.reset();
    }
    if (resume && !fs::exists(run_config_path(out))) resume.reset();
    if (resume) {
      Checkpoint ck = read_checkpoint(*resume, Device::CPU);
      state = std::move(ck.state);
      if (device != Device::CPU) state.model = state.model.copy_to(device);
      Trainer::load_renderer_state(*resume, *renderer);
    } else {
      state.model = std::move(lifted);
      state.rng.seed(ft.seed + 2);
      if (const auto s1 = latest_checkpoint(run_dir)) Trainer::load_renderer_state(*s1, *renderer);
    }
    write_run_config(out, ft);
    if (!resume) write_made_from(record, finetune_from);  // before the first checkpoint, which it describes
    Trainer trainer(ft, std::move(views), extent, renderer, std::move(state));
    Trainer::RunOptions ro;
    ro.run_dir = out;
    ro.stop = stop;
    ro.progress_every = 10;
    ro.on_progress = [&](const TrainProgress& p) {
      char b[160];
      std::snprintf(b, sizeof b, "loss %.4f  PSNR %.2f dB  %.1f it/s", p.loss, p.psnr, p.it_per_s);
      s.tell(std::size_t(p.iteration), std::size_t(p.total), b);
    };
    const Trainer::RunResult rr = trainer.run(ro);
    report.finetune_iterations = trainer.state().iteration;
    report.gaussians_after = trainer.model().count();
    if (rr == Trainer::RunResult::Stopped) {
      report.cancelled = true;
      return report;
    }
    write_ply(run_ply_path(out), trainer.model().to_ply(/*bake_3d_filter=*/true));
    nlohmann::json j;
    j["selected"] = report.selected;
    j["gaussians_before"] = report.gaussians_before;
    j["gaussians_after"] = report.gaussians_after;
    j["added_by_lift"] = report.added;
    j["lighting_mask_pixels"] = report.lighting_pixels;
    j["mirror_twins"] = report.mirror_twins;
    j["underside"] = report.underside;
    j["reflection_pixels"] = report.reflection_pixels;
    j["lift_onto_plane_pixels"] = report.lift_onto_plane_pixels;
    if (report.glossy_plane.found)
      j["glossy_plane"] = {{"normal", {report.glossy_plane.normal.x, report.glossy_plane.normal.y, report.glossy_plane.normal.z}},
                           {"offset", report.glossy_plane.offset},
                           {"inliers", report.glossy_plane.inliers},
                           {"candidates", report.glossy_plane.candidates}};
    j["lighting_fresnel_reference"] = report.lighting_fresnel_reference;
    j["dereflected_pixels"] = report.dereflected_pixels;
    j["reflection_photo_pixels"] = report.reflection_photo_pixels;
    j["shadow"] = {{"found", report.shadow_found}, {"summary", report.shadow}, {"relit_pixels", report.shadow_pixels}};
    j["inpaint_mask_pixels"] = report.inpaint_pixels;
    j["glossy_mask_filled_pixels"] = report.glossy_filled_pixels;
    j["reference_views"] = report.reference_views;
    j["material_targets"] = {{"surface_detail", report.surface_detail}, {"weight", report.material_weight}};
    j["finetune_iterations"] = report.finetune_iterations;
    j["finetune_targets"] = {{"excluded_pixels", fs_stats.excluded_pixels},
                             {"appearance_pixels", fs_stats.appearance_pixels},
                             {"material_pixels", fs_stats.material_pixels},
                             {"projected_points", fs_stats.projected_points},
                             {"filled_pixels", fs_stats.filled_pixels}};
    if (!o.fill_truth.empty()) {
      j["fill_truth_pixels"] = report.fill_truth_pixels;
      // In units of the target's imprint on the photos (as the ghost ratio): what the photos the fine-tune
      // trains on carry of the target, as taken and as trained (dereflected, relit).
      const PhotoTargetsTruthError& e = report.truth_error;
      const double imprint = e.imprint > 0 ? e.imprint : 1.0;
      j["photo_targets_against_truth"] = {{"imprint", e.imprint},
                                          {"trained_pixels", e.trained_pixels},
                                          {"photos_as_taken", e.photos / imprint},
                                          {"photos_as_trained", e.targets / imprint},
                                          {"changed_pixels", e.changed_pixels},
                                          {"changed_as_taken", e.changed_photos / imprint},
                                          {"changed_as_trained", e.changed_targets / imprint}};
    }
    j["options"] = options_json(o);
    j["made_from"] = finetune_from;
    j["peak_host_memory_mib"] = peak_host_memory_mib();
    s.finish("done");
    for (int k = 0; k < kRemovalStepCount; ++k) j["seconds"][removal_step_name(RemovalStep(k))] = report.seconds[k];
    write_json_file(out / "report.json", j);
  }
  return report;
}

}  // namespace goris
