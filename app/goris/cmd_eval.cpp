// `goris eval RUN --split test [--gt after|full]`: image metrics of a trained run against the ground truth,
// written to RUN/metrics.json (or --out) through a temporary file.
//
// PSNR and SSIM (the 3DGS definitions, train/losses/image_losses.h) per view, then averaged over views.
// Masked metrics (M-PSNR, M-SSIM) use the view's object mask (test/mask_XXX.png): they are computed on the
// crop given by the bounding box of the mask pixels >= 0.5, grown by 10% of its width / height on each
// side (at least 4 pixels) and clamped to the image; views whose mask is empty are left out of the
// masked means. A crop rather than the exact mask keeps SSIM's 11x11 windows meaningful at the edges.
//
// Every view also gets LDR-FLIP (core/metrics/flip.h) over the whole image. Against the after-removal ground
// truth of a GOR-IS-style set (test views with full_XXX.png) the "removal" block measures what the removal
// had to fix (core/metrics/removal_metrics.h): PSNR, SSIM and FLIP inside the changed region (where full_ and
// r_ differ), the ghost ratio over it (pooled over the views: sum |render - r_| / sum |full_ - r_|, after a
// 3x3 median), for a removal folder its floor (the same sum for its stage-1 run RUN/.. against full_: how far
// the model the removal started from is from the photos there), and a contact sheet of the views with the
// largest changed regions (METRICS_removal.png beside the metrics file).
//
// Runs with material channels on a data set with true normals (`goris synth`: train/gt/normal_XXX.exr) also
// get "intrinsic_ground_truth": normal angular error, roughness and F0 on the training views' glossy
// surface (train/intrinsic/intrinsic_accuracy.h). Intrinsic runs on a data set with glossy masks get
// "materials": roughness, F0 and M on the glossy surface against the rest, and how well roughness alone
// separates the two (train/intrinsic/material_separation.h), and "reflections": the share of the glossy
// surface's colour the traced glossy term carries (train/intrinsic/glossy_share.h).
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_common/command.h"
#include "core/io/json_file.h"
#include "core/io/dataset.h"
#include "core/io/file_bytes.h"
#include "core/io/image.h"
#include "core/metrics/removal_metrics.h"
#include "train/losses/image_losses.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "core/compute/bench.h"
#include "train/run/run_output_guard.h"
#include "core/util/error.h"
#include "core/compute/memory.h"
#include "train/run/normal_prior.h"
#include "train/intrinsic/intrinsic_accuracy.h"
#include "train/intrinsic/material_separation.h"
#include "train/intrinsic/glossy_share.h"
#include "train/setup/run_renderer.h"
#include "train/radiance/raster_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, split = "test", gt = "after", out, device = "auto", data;
};

struct Crop {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // exclusive ends
  int w() const { return x1 - x0; }
  int h() const { return y1 - y0; }
};

std::optional<Crop> mask_crop(const Image& mask) {
  const std::vector<float> m = mask.pixels.to_host();
  Crop c{mask.width, mask.height, -1, -1};
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (m[size_t(y) * mask.width + x] >= 0.5f) {
        c.x0 = std::min(c.x0, x);
        c.y0 = std::min(c.y0, y);
        c.x1 = std::max(c.x1, x + 1);
        c.y1 = std::max(c.y1, y + 1);
      }
  if (c.x1 < 0) return std::nullopt;
  const int gx = std::max(4, int(std::ceil(0.1 * c.w()))), gy = std::max(4, int(std::ceil(0.1 * c.h())));
  c.x0 = std::max(0, c.x0 - gx);
  c.y0 = std::max(0, c.y0 - gy);
  c.x1 = std::min(mask.width, c.x1 + gx);
  c.y1 = std::min(mask.height, c.y1 + gy);
  return c;
}

std::vector<float> crop_planar(const std::vector<float>& img, int w, int h, const Crop& c) {
  std::vector<float> out(size_t(3) * c.w() * c.h());
  for (int ch = 0; ch < 3; ++ch)
    for (int y = 0; y < c.h(); ++y)
      for (int x = 0; x < c.w(); ++x)
        out[(size_t(ch) * c.h() + y) * c.w() + x] = img[(size_t(ch) * h + c.y0 + y) * w + c.x0 + x];
  return out;
}

double mean_of(const std::vector<double>& v) {
  if (v.empty()) return std::nan("");
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// One row of the removal contact sheet: full_ | r_ | render | |render - r_| x 4, planar [3][H][W] each.
struct SheetRow {
  double region_fraction = 0;
  std::vector<float> before, after, render;
};

// The sheet of up to `rows` views (those with the largest changed regions), columns as in SheetRow, 2 px gaps.
void write_removal_sheet(std::vector<SheetRow> views, int w, int h, const fs::path& path, size_t rows = 4) {
  std::stable_sort(views.begin(), views.end(),
                   [](const SheetRow& a, const SheetRow& b) { return a.region_fraction > b.region_fraction; });
  views.resize(std::min(views.size(), rows));
  if (views.empty()) return;
  const int gap = 2, cols = 4, W = cols * w + (cols - 1) * gap, H = int(views.size()) * h + (int(views.size()) - 1) * gap;
  Image sheet;
  sheet.width = W, sheet.height = H, sheet.channels = 3;
  std::vector<float> px(size_t(W) * H * 3, 1.0f);
  for (size_t r = 0; r < views.size(); ++r)
    for (int c = 0; c < cols; ++c)
      for (int ch = 0; ch < 3; ++ch)
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const size_t i = (size_t(ch) * h + y) * w + x;
            const SheetRow& v = views[r];
            const float value = c == 0 ? v.before[i] : c == 1 ? v.after[i] : c == 2 ? v.render[i]
                                                                             : std::min(1.0f, 4.0f * std::abs(v.render[i] - v.after[i]));
            const int X = c * (w + gap) + x, Y = int(r) * (h + gap) + y;
            px[(size_t(Y) * W + X) * 3 + ch] = value;
          }
  sheet.pixels = Buffer<float>(px, Device::CPU);
  save_png(path, sheet);
}

// Normals for every run (a radiance run's geometry has normals too); materials only where they were learned.
// Adds j["intrinsic_ground_truth"] when the data set has true normals (train/gt/normal_*.exr).
// The training views that have a glossy mask, with it loaded.
std::vector<TrainView> glossy_train_views(const Dataset& ds) {
  std::vector<TrainView> tv;
  for (const View& v : ds.train) {
    if (!v.glossy_mask) continue;
    TrainView t;
    t.name = v.name;
    t.camera = v.camera;
    t.glossy_mask = load_view_glossy_mask(v).pixels.to_host();
    tv.push_back(std::move(t));
  }
  return tv;
}

// `glossy_views`: glossy_train_views(), read once per evaluation by the measures below.
std::optional<IntrinsicAccuracy> intrinsic_ground_truth(const TrainConfig& config,
                                                        const std::vector<TrainView>& glossy_views,
                                                        GaussianModel& model, Device device, nlohmann::json& j) {
  const auto gt_dir = ground_truth_normal_dir(config.input.data);
  if (!gt_dir || glossy_views.empty()) return std::nullopt;
  std::vector<TrainView> tv = glossy_views;  // with the true normals added
  load_normal_priors(*gt_dir, tv);
  IntrinsicAccuracy acc;
  try {
    acc = measure_intrinsic_accuracy(model.view(true), tv, RasterRenderer::settings_for(config), device,
                                     glossy_reference_from_scene(fs::path(config.input.data) / "scene.json"));
  } catch (const Error& e) {  // e.g. a scene whose glossy masks are empty (a Lambertian room): nothing to measure
    j["intrinsic_ground_truth"] = {{"not_measured", e.what()}};
    std::printf("intrinsic ground truth: not measured (%s)\n", e.what());
    return std::nullopt;
  }
  nlohmann::json ja = {{"views", acc.views},
                       {"pixels", acc.pixels},
                       {"normal_mean_deg", acc.normal_mean_deg},
                       {"normal_median_deg", acc.normal_median_deg},
                       {"where", "training views, glossy mask >= 0.5, alpha >= 0.5; truth " + gt_dir->string()}};
  if (config.mode == TrainMode::Intrinsic) {
    ja["roughness_mean"] = acc.roughness_mean;
    ja["f0_mean"] = {acc.f0_mean.x, acc.f0_mean.y, acc.f0_mean.z};
    if (acc.reference) {
      ja["roughness_reference"] = acc.reference->roughness;
      ja["roughness_mae"] = acc.roughness_mae;
      ja["f0_reference"] = {acc.reference->f0.x, acc.reference->f0.y, acc.reference->f0.z};
      ja["f0_mae"] = acc.f0_mae;
    }
  }
  j["intrinsic_ground_truth"] = ja;
  return acc;
}

nlohmann::json material_stats_json(const MaterialStats& m) {
  return {{"pixels", m.pixels},          {"roughness_median", m.roughness_median}, {"roughness_mean", m.roughness_mean},
          {"f0_median", m.f0_median},    {"f0_mean", m.f0_mean},                   {"region_median", m.region_median},
          {"region_mean", m.region_mean}};
}

// Intrinsic runs on a data set with glossy masks: the materials on the glossy surface against the rest
// (train/intrinsic/material_separation.h); j["materials"].
std::optional<MaterialSeparation> material_separation(const TrainConfig& config, const std::vector<TrainView>& tv,
                                                      GaussianModel& model, Device device, nlohmann::json& j) {
  if (config.mode != TrainMode::Intrinsic || tv.empty()) return std::nullopt;
  MaterialSeparation s;
  try {
    s = measure_material_separation(model.view(true), tv, RasterRenderer::settings_for(config), device);
  } catch (const Error& e) {  // e.g. a run that never became opaque on the glossy surface: no report, no failure
    j["materials"] = {{"not_measured", e.what()}};
    std::printf("materials: not measured (%s)\n", e.what());
    return std::nullopt;
  }
  j["materials"] = {{"views", s.views},
                    {"where", "training views, alpha >= 0.5; glossy: glossy mask >= 0.5, rest: < 0.5"},
                    {"glossy", material_stats_json(s.glossy)},
                    {"rest", material_stats_json(s.rest)},
                    {"roughness_auc", s.roughness_auc}};
  return s;
}

// An intrinsic model on a data set with glossy masks: how much of the glossy surface's colour the traced
// glossy term carries (train/intrinsic/glossy_share.h); nullopt for a radiance model or without masks.
std::optional<GlossyShare> glossy_share_of(const std::vector<TrainView>& tv, GaussianModel& model,
                                           DifferentiableRenderer& renderer) {
  IntrinsicRenderer* intrinsic = as_intrinsic(&renderer);
  if (!intrinsic || tv.empty()) return std::nullopt;
  return measure_glossy_share(*intrinsic, model.view(true), tv);
}

void run_eval(const Options& o) {
  const fs::path run_dir = fs::absolute(o.run);
  const TrainConfig config = read_run_config_with_data(run_dir, o.data);
  const fs::path out = o.out.empty() ? run_dir / "metrics.json" : fs::absolute(o.out);
  check_output_file(out, run_output_guard(run_dir, config));  // never into the data set or over the run's files
  const Device device = resolve_device(o.device);
  const DatasetOptions dopt = dataset_options(config);
  const Dataset ds = load_dataset(config.input.data, dopt);
  const std::vector<View>& views = o.split == "test" ? ds.test : ds.train;
  if (views.empty()) throw Error(config.input.data, "the data set has no " + o.split + " views");
  std::string source;
  GaussianModel model = load_run_model(run_dir, device, &source);
  const auto renderer = load_run_renderer(run_dir, config, scene_extent(ds), device);

  // A removal folder's stage-1 run is RUN/..: its own render of the scene with the target, against full_
  // over the changed region, is the ghost's floor (region_residual, core/metrics/removal_metrics.h).
  const bool removal = fs::exists(run_dir / "report.json");
  struct Stage1 {
    GaussianModel model;
    std::shared_ptr<DifferentiableRenderer> renderer;
    std::string source;
  };
  std::optional<Stage1> stage1;
  std::string floor_note;
  if (o.gt == "after" && removal) {
    try {
      const fs::path parent = run_dir.parent_path();
      const TrainConfig c1 = read_run_config_with_data(parent, o.data);
      Stage1 s1;
      s1.model = load_run_model(parent, device, &s1.source);
      s1.renderer = load_run_renderer(parent, c1, scene_extent(ds), device);
      stage1 = std::move(s1);
    } catch (const Error& e) {  // a removal folder without its stage-1 run beside it: no floor, no failure
      floor_note = e.what();
    }
  }
  auto render_view = [&](GaussianModel& m, DifferentiableRenderer& rr, const Camera& cam) {
    const RenderedImages r = rr.forward(m.view(rr.wants_extras()), cam);
    std::vector<float> img(3 * size_t(cam.width) * cam.height);
    device_copy(img.data(), Device::CPU, r.color, device, img.size() * sizeof(float));
    return img;
  };
  double floor_num = 0;

  nlohmann::json per_view = nlohmann::json::array();
  std::vector<double> psnrs, ssims, m_psnrs, m_ssims, flips, region_psnrs, region_ssims, region_flips, region_fractions;
  double ghost_num = 0, ghost_den = 0;  // pooled over the views
  std::vector<SheetRow> sheet;
  double render_ms = 0;
  size_t non_finite = 0;  // NaN / Inf in the renders (clamping below would hide an Inf)
  for (const View& v : views) {
    if (o.gt == "full" && !v.full_image)
      throw Error(v.image.string(), "--gt full: this view has no full_XXX.png (not a GOR-IS-style data set?)");
    const Image gt_img = o.gt == "full" ? load_view_full_image(v, dopt) : load_view_image(v, dopt);
    const int w = v.camera.width, h = v.camera.height;
    if (gt_img.width != w || gt_img.height != h) throw Error(v.image.string(), "ground truth size differs from the camera");
    const std::vector<float> gt = to_planar_rgb(gt_img);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<float> pred = render_view(model, *renderer, v.camera);
    render_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    non_finite += size_t(std::count_if(pred.begin(), pred.end(), [](float x) { return !std::isfinite(x); }));
    std::vector<float> clamped(pred.size());
    for (size_t i = 0; i < pred.size(); ++i) clamped[i] = std::clamp(pred[i], 0.0f, 1.0f);  // as a saved image

    nlohmann::json jv;
    jv["name"] = v.name;
    const double psnr = psnr_from_mse(mse<float>(clamped.data(), gt.data(), gt.size()));
    const double s = ssim<float>(clamped.data(), gt.data(), 3, w, h);
    psnrs.push_back(psnr);
    ssims.push_back(s);
    jv["psnr"] = number_or_null(psnr);
    jv["ssim"] = s;
    if (o.gt == "after" && v.full_image) {
      const std::vector<float> before = to_planar_rgb(load_view_full_image(v, dopt));
      const RemovalMetrics rm = removal_metrics(clamped.data(), gt.data(), before.data(), w, h);
      flips.push_back(rm.flip);
      jv["flip"] = rm.flip;
      jv["region_fraction"] = rm.region_fraction;
      region_fractions.push_back(rm.region_fraction);
      if (rm.region_fraction > 0) {
        region_psnrs.push_back(rm.region_psnr), region_ssims.push_back(rm.region_ssim);
        region_flips.push_back(rm.region_flip);
        jv["region_psnr"] = number_or_null(rm.region_psnr);
        jv["region_ssim"] = rm.region_ssim;
        jv["region_flip"] = rm.region_flip;
        jv["ghost_ratio"] = number_or_null(rm.ghost_ratio);
        ghost_num += rm.ghost_residual, ghost_den += rm.ghost_imprint;
        if (stage1) {
          std::vector<float> s1 = render_view(stage1->model, *stage1->renderer, v.camera);
          for (float& x : s1) x = std::clamp(x, 0.0f, 1.0f);
          floor_num += region_residual(s1.data(), before.data(), rm.region, w, h);
        }
      }
      sheet.push_back({rm.region_fraction, before, gt, clamped});
    } else {
      const double f = flip_mean(clamped.data(), gt.data(), w, h);
      flips.push_back(f);
      jv["flip"] = f;
    }
    if (v.object_mask) {
      if (const auto c = mask_crop(load_view_object_mask(v))) {
        const auto cp = crop_planar(clamped, w, h, *c), cg = crop_planar(gt, w, h, *c);
        const double mp = psnr_from_mse(mse<float>(cp.data(), cg.data(), cg.size()));
        const double ms = ssim<float>(cp.data(), cg.data(), 3, c->w(), c->h());
        m_psnrs.push_back(mp);
        m_ssims.push_back(ms);
        jv["m_psnr"] = number_or_null(mp);
        jv["m_ssim"] = ms;
        jv["mask_crop"] = {c->x0, c->y0, c->x1, c->y1};
      }
    }
    per_view.push_back(jv);
  }

  nlohmann::json j;
  j["run"] = run_dir.string();
  j["model"] = source;
  j["data"] = config.input.data;
  j["split"] = o.split;
  j["gt"] = o.gt == "full" ? "full: test views with the target (full_XXX.png)" : "after: the views' images (r_XXX.png)";
  j["views"] = views.size();
  j["resolution"] = {views[0].camera.width, views[0].camera.height};
  j["gaussians"] = model.count();
  j["device"] = device_name(device);
  j["psnr"] = number_or_null(mean_of(psnrs));
  j["ssim"] = mean_of(ssims);
  j["masked"] = {{"psnr", number_or_null(mean_of(m_psnrs))},
                 {"ssim", number_or_null(mean_of(m_ssims))},
                 {"views", m_psnrs.size()},
                 {"region", "bounding box of the object mask (>= 0.5), grown by 10% per side (min 4 px)"}};
  j["flip"] = number_or_null(mean_of(flips));
  const fs::path sheet_path = out.parent_path() / (out.stem().string() + "_removal.png");
  if (!region_fractions.empty()) {
    j["removal"] = {{"views", region_psnrs.size()},
                    {"region_fraction", mean_of(region_fractions)},
                    {"region_psnr", number_or_null(mean_of(region_psnrs))},
                    {"region_ssim", number_or_null(mean_of(region_ssims))},
                    {"region_flip", number_or_null(mean_of(region_flips))},
                    {"ghost_ratio", number_or_null(ghost_den > 1e-9 ? ghost_num / ghost_den : std::nan(""))},
                    {"ghost_floor", number_or_null(stage1 && ghost_den > 1e-9 ? floor_num / ghost_den : std::nan(""))},
                    {"contact_sheet", sheet_path.filename().string()},
                    {"region", "pixels where full_ and r_ differ by > 0.04 (max over RGB) after a 3x3 median, "
                               "dilated 2 px; means over the views with such pixels, the ghost ratio pooled"}};
    j["removal"]["ghost_floor_model"] = stage1 ? stage1->source : "not measured: " + (removal ? floor_note : "not a removal folder");
    write_removal_sheet(std::move(sheet), views[0].camera.width, views[0].camera.height, sheet_path);
  }
  j["non_finite_values"] = non_finite;
  j["render_ms_mean"] = render_ms / double(views.size());
  j["peak_host_memory_mib"] = peak_host_memory_mib();
  // Time per stage and peak memory of the run itself: stage 1 from its training log, stage 2 from the removal
  // report (when RUN is a removal folder, RUN/.. is its stage-1 run).
  auto training_seconds = [](const fs::path& dir) -> std::optional<double> {
    std::ifstream in(dir / "log.csv");
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) last = line;
    if (last.empty()) return std::nullopt;
    // iteration,loss,psnr,gaussians,elapsed_s,it_per_s
    size_t pos = 0;
    for (int k = 0; k < 4 && pos != std::string::npos; ++k) pos = last.find(',', pos) + 1;
    return pos ? std::optional<double>(std::atof(last.c_str() + pos)) : std::nullopt;
  };
  nlohmann::json stages = nlohmann::json::object();
  if (const auto t = training_seconds(removal ? run_dir.parent_path() : run_dir)) stages["stage 1 training"] = *t;
  if (removal) {
    const nlohmann::json rep = nlohmann::json::parse(read_text_file(run_dir / "report.json"), nullptr, false);
    if (rep.is_object() && rep.contains("seconds"))
      for (auto it = rep["seconds"].begin(); it != rep["seconds"].end(); ++it) stages["stage 2 " + it.key()] = it.value();
    if (rep.is_object() && rep.contains("peak_host_memory_mib")) j["removal_peak_host_memory_mib"] = rep["peak_host_memory_mib"];
  }
  j["stage_seconds"] = stages;
  const std::vector<TrainView> glossy_views = glossy_train_views(ds);
  const std::optional<IntrinsicAccuracy> acc = intrinsic_ground_truth(config, glossy_views, model, device, j);
  const bool materials = config.mode == TrainMode::Intrinsic;
  const std::optional<MaterialSeparation> sep = material_separation(config, glossy_views, model, device, j);
  // "reflections": this model's share, and for a removal folder its stage-1 model's (the decomposition the
  // removal started from).
  const std::optional<GlossyShare> share = glossy_share_of(glossy_views, model, *renderer);
  const std::optional<GlossyShare> share1 = stage1 ? glossy_share_of(glossy_views, stage1->model, *stage1->renderer)
                                                   : std::nullopt;
  auto share_json = [](const std::optional<GlossyShare>& g) {
    return g && g->share() ? nlohmann::json(*g->share()) : nlohmann::json(nullptr);
  };
  if (share || share1)
    j["reflections"] = {{"glossy_share", share_json(share)},
                        {"stage1_glossy_share", share_json(share1)},
                        {"where", "training views, glossy mask >= 0.5: sum (C - D) / sum C over their pixels and "
                                  "RGB (C = D + (1 - M) G)"}};
  j["per_view"] = per_view;

  write_json_file(out, j);
  std::printf("%s split (%zu views at %dx%d, gt %s): PSNR %.2f dB  SSIM %.4f", o.split.c_str(), views.size(),
              views[0].camera.width, views[0].camera.height, o.gt.c_str(), mean_of(psnrs), mean_of(ssims));
  if (!m_psnrs.empty()) std::printf("  M-PSNR %.2f dB  M-SSIM %.4f (%zu views)", mean_of(m_psnrs), mean_of(m_ssims), m_psnrs.size());
  std::printf("  FLIP %.4f\n", mean_of(flips));
  if (j.contains("removal") && !region_psnrs.empty())
    std::printf("changed region (%.1f %% of the pixels, %zu views): PSNR %.2f dB  SSIM %.4f  FLIP %.4f  ghost %.3f "
                "(contact sheet %s)\n",
                100 * mean_of(region_fractions), region_psnrs.size(), mean_of(region_psnrs), mean_of(region_ssims),
                mean_of(region_flips), ghost_den > 1e-9 ? ghost_num / ghost_den : std::nan(""), sheet_path.c_str());
  if (j.contains("removal") && stage1 && ghost_den > 1e-9)
    std::printf("ghost floor %.3f: stage 1 (%s) against the views with the target over the same region\n",
                floor_num / ghost_den, stage1->source.c_str());
  if (acc) {
    std::printf("against the true intrinsics (%zu training views, %zu glossy pixels): normal error %.1f deg mean, %.1f "
                "median", acc->views, acc->pixels, acc->normal_mean_deg, acc->normal_median_deg);
    if (materials) std::printf("; roughness %.3f", acc->roughness_mean);
    if (materials && acc->reference)
      std::printf(" (true %.3f, MAE %.3f); F0 MAE %.3f (true %.2f %.2f %.2f)", double(acc->reference->roughness),
                  acc->roughness_mae, acc->f0_mae, double(acc->reference->f0.x), double(acc->reference->f0.y),
                  double(acc->reference->f0.z));
    std::printf("\n");
  }
  if (sep)
    std::printf("materials (%zu training views, median): glossy surface roughness %.3f F0 %.3f M %.2f; rest roughness "
                "%.3f F0 %.3f M %.2f; roughness separates them with AUC %.2f\n",
                sep->views, sep->glossy.roughness_median, sep->glossy.f0_median, sep->glossy.region_median,
                sep->rest.roughness_median, sep->rest.f0_median, sep->rest.region_median, sep->roughness_auc);
  if (share && share->share()) {
    char s1[64] = "";
    if (share1 && share1->share()) std::snprintf(s1, sizeof s1, "; stage 1: %.1f %%", 100 * *share1->share());
    std::printf("reflections: the glossy term carries %.1f %% of the glossy surface's colour, D the rest%s\n",
                100 * *share->share(), s1);
  }
  std::printf("metrics: %s\n", out.string().c_str());
}

void setup_eval(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("eval", "Compute PSNR / SSIM (and masked versions) of a trained run");
  c->add_option("run", o->run, "Run folder written by `goris train`")->required();
  c->add_option("--split", o->split, "Which views: test or train")->check(CLI::IsMember({"test", "train"}));
  c->add_option("--gt", o->gt,
                "Ground truth: after (the views' images; for GOR-IS sets the scene after removal) or full "
                "(GOR-IS test/full_XXX.png, the scene with the target)")
      ->check(CLI::IsMember({"after", "full"}));
  c->add_option("--out", o->out, "Metrics file (default RUN/metrics.json)");
  cli::add_device_option(*c, o->device);
  cli::add_data_option(*c, o->data);
  c->callback([o] { run_eval(*o); });
}

}  // namespace
GORIS_COMMAND(45, setup_eval);
