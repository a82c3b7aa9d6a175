#include "train/setup/auto_mode.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/io/image.h"
#include "core/io/json_file.h"
#include "core/util/error.h"
#include "train/radiance/raster_renderer.h"
#include "train/run/normal_prior.h"
#include "train/run/run_folder.h"
#include "train/setup/glossy_detection.h"
#include "train/setup/run_renderer.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

std::string percent(double f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f %%", 100.0 * f);
  return buf;
}

fs::path mask_file(const fs::path& dir, const TrainView& v) { return dir / ("gloss_" + v.name + ".png"); }

template <class T>
void save_mask_values(const fs::path& dir, const TrainView& v, const std::vector<T>& values) {
  const Camera& c = v.camera;
  Image m(c.width, c.height, 1);
  for (size_t p = 0; p < values.size() && p < m.pixels.size(); ++p) m.pixels[p] = float(values[p]);
  save_png(mask_file(dir, v), m);
}

void write_masks(const fs::path& dir, const std::vector<TrainView>& views, const GlossyDetection& det) {
  fs::create_directories(dir);
  for (size_t i = 0; i < views.size(); ++i) save_mask_values(dir, views[i], det.masks[i]);
}

void write_summary(const fs::path& dir, const std::vector<TrainView>& views, const GlossyDetection& det,
                   const GlossyDetectionSettings& s, const AutoDecision& d) {
  nlohmann::json j;
  j["iteration"] = d.iteration;
  j["decision"] = d.glossy ? "intrinsic" : "radiance";
  j["fraction"] = d.fraction;
  j["threshold"] = d.threshold;
  j["covered_pixels"] = d.covered;
  j["scored_pixels"] = d.scored;
  j["detected_pixels"] = d.detected;
  j["planes"] = d.planes;
  j["plane_in_front"] = det.plane_in_front;  // per plane found: share of the detections in front of its surface
  j["mask_pixels"] = d.mask_pixels;
  j["mirror_world"] = {{"found", det.mirror_world.found},
                       {"summary", det.mirror_world.summary},
                       {"decided", d.mirror_world}};
  j["seconds"] = d.seconds;
  j["settings"] = {{"neighbours", s.neighbours},         {"pixel_threshold", s.threshold},
                   {"depth_tolerance", s.depth_tolerance}, {"search_radius", s.search_radius},
                   {"min_visible", s.min_visible},       {"morph_radius", s.morph_radius},
                   {"work_width", s.work_width},         {"plane_tolerance", s.grow_planes ? s.plane_tolerance : 0.0f},
                   {"plane_max_in_front", s.plane_max_in_front}};
  nlohmann::json per_view = nlohmann::json::array();
  for (size_t i = 0; i < views.size(); ++i) {
    size_t n = 0;
    for (const std::uint8_t b : det.masks[i]) n += b;
    per_view.push_back({{"view", views[i].name}, {"mask_fraction", det.masks[i].empty() ? 0.0 : double(n) / double(det.masks[i].size())}});
  }
  j["views"] = per_view;
  write_json_file(dir / "summary.json", j);
}

}  // namespace

std::optional<double> glossy_mask_fraction(const std::vector<TrainView>& views) {
  size_t glossy = 0, total = 0;
  for (const TrainView& v : views) {
    total += v.glossy_mask.size();
    for (const float x : v.glossy_mask) glossy += x > 0.5f;
  }
  if (total == 0) return std::nullopt;
  return double(glossy) / double(total);
}

std::string resolve_auto_mode(TrainConfig& config, const std::vector<TrainView>& views) {
  if (config.mode != TrainMode::Auto) return {};
  const std::optional<double> f = glossy_mask_fraction(views);
  const double threshold = config.intrinsic.auto_mask_fraction;
  if (f) {
    const bool glossy = *f > 0 && *f >= threshold;
    config.mode = glossy ? TrainMode::Intrinsic : TrainMode::Radiance;
    return glossy ? "the glossy masks mark " + percent(*f) + " of the pixels, threshold " + percent(threshold)
                  : "the glossy masks are empty: " + percent(*f) + " of the pixels, threshold " + percent(threshold);
  }
  config.mode = TrainMode::Radiance;
  config.input.auto_detect_glossy = true;
  const int at = auto_detection_iteration(config);
  std::string why = "no glossy masks: radiance through the warm-up, then glossy regions are detected from the photos after "
                    "iteration " + std::to_string(at);
  if (at < config.intrinsic.detect_settled)
    why += "; caution: a run this short decides before the geometry has settled (" +
           std::to_string(config.intrinsic.detect_settled) +
           " iterations), when a Lambertian scene can look glossy - give glossy masks (gloss_*.png), train longer "
           "or choose --mode radiance|intrinsic";
  return why;
}

int planned_shading_start(const TrainConfig& config) {
  return std::max(config.shading_from(), std::min(config.intrinsic.detect_after, config.iterations / 2));
}

int auto_detection_iteration(const TrainConfig& config) {
  const int at = std::max(planned_shading_start(config), std::min(config.intrinsic.detect_settled, config.iterations));
  // Not on a model whose opacities a reset has just lowered (Trainer::densify): it renders next to nothing,
  // and the detection would see no surface at all. The iteration before that reset instead.
  const int every = config.opacity_reset_every(), interval = std::max(config.densify.interval, 1);
  const int reset = every > 0 ? at / every * every : 0;
  const bool resets_there = reset > 0 && reset + interval <= config.densify_until();
  return resets_there && at - reset < interval ? reset - 1 : at;
}

TrainConfig lengthened_for_late_decision(const TrainConfig& config, int decided_at) {
  const int planned = planned_shading_start(config);
  TrainConfig c = config;
  if (decided_at <= planned) return c;
  c.iterations = decided_at + std::max(config.iterations - planned, 0);
  return c;
}

namespace {

// The smallest warm-up (in full-schedule iterations) whose TrainConfig::shading_from is `iteration` or later,
// so that the shading phase's schedules (environment-map learning rate, the net's ease-in) start at the switch.
// shading_from grows monotonically with the warm-up, so a bisection finds it.
int warmup_ending_at(const TrainConfig& config, int iteration) {
  TrainConfig c = config;
  // At hi the scaled warm-up alone reaches `iteration`.
  int lo = 0, hi = int(std::min<long long>(1LL << 30, 30000LL * iteration / std::max(config.iterations, 1) + 30000));
  while (lo < hi) {
    c.intrinsic.warmup = lo + (hi - lo) / 2;
    if (c.shading_from() >= iteration) hi = c.intrinsic.warmup;
    else lo = c.intrinsic.warmup + 1;
  }
  return lo;
}

}  // namespace

void load_glossy_mask_folder(const fs::path& dir, std::vector<TrainView>& views) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "glossy mask folder (glossy_mask_dir) not found");
  for (TrainView& v : views) {
    const fs::path f = mask_file(dir, v);
    if (!fs::exists(f)) throw Error(f.string(), "missing: the glossy mask of training view " + v.name);
    const Image m = load_mask(f);
    if (m.width != v.camera.width || m.height != v.camera.height)
      throw Error(f.string(), "is " + std::to_string(m.width) + "x" + std::to_string(m.height) + ", the training view is " +
                                  std::to_string(v.camera.width) + "x" + std::to_string(v.camera.height) +
                                  " (masks in glossy_mask_dir are stored at the training size)");
    v.glossy_mask = m.pixels.to_host();
  }
}

std::vector<std::vector<float>> run_glossy_masks(const TrainConfig& config, const std::vector<View>& views) {
  std::vector<TrainView> tv;
  for (const View& v : views) {
    tv.emplace_back().name = v.name;
    tv.back().camera = v.camera;
    if (v.glossy_mask && config.input.use_glossy_masks && config.input.glossy_mask_dir.empty())
      tv.back().glossy_mask = load_view_glossy_mask(v).pixels.to_host();
  }
  if (!config.input.glossy_mask_dir.empty()) load_glossy_mask_folder(config.input.glossy_mask_dir, tv);
  std::vector<std::vector<float>> out;
  for (TrainView& v : tv) out.push_back(std::move(v.glossy_mask));
  return out;
}

void save_glossy_mask_folder(const fs::path& dir, const std::vector<TrainView>& views) {
  fs::create_directories(dir);
  for (const TrainView& v : views) {
    if (v.glossy_mask.empty()) throw Error(mask_file(dir, v).string(), "training view " + v.name + " has no glossy mask to write");
    save_mask_values(dir, v, v.glossy_mask);
  }
}

std::string AutoDecision::message() const {
  char secs[32];
  std::snprintf(secs, sizeof secs, "%.1f s", seconds);
  const std::string found = percent(fraction) + " of the covered pixels look view-dependent, threshold " + percent(threshold);
  const std::string grown = planes > 0 ? ", grown over " + std::to_string(planes) + (planes == 1 ? " plane" : " planes") +
                                             " to " + percent(covered ? double(mask_pixels) / double(covered) : 0.0)
                                       : "";
  const std::string why = (mirror_world ? "a mirror world behind a plane (" : "glossy regions (") + found + grown + ")";
  return "--mode auto after iteration " + std::to_string(iteration) + ": " +
         (glossy ? why + " -> intrinsic from now on with the masks in " + mask_dir.string()
                 : "no glossy regions (" + found +
                       (backdrops > 0             ? ", most of it in front of the plane it was found near: not a reflector"
                        : fraction >= threshold ? ", on no plane"
                                                : "") +
                       ") -> radiance to the end; masks in " + mask_dir.string()) +
         (extended_by > 0 ? "; the run grows by " + std::to_string(extended_by) +
                                " iterations so that the shading phase keeps its planned length"
                          : "") +
         " (detection " + secs + ")";
}

std::optional<AutoDecision> apply_auto_mode(Trainer& trainer, const fs::path& run_dir) {
  const TrainConfig& config = trainer.config();
  if (!config.input.auto_detect_glossy || trainer.state().iteration < auto_detection_iteration(config))
    return std::nullopt;
  if (run_dir.empty()) throw Error("--mode auto: the glossy detection needs a run folder for its masks");
  const auto t0 = std::chrono::steady_clock::now();
  const GlossyDetectionSettings s = GlossyDetectionSettings::from_config(config);
  const GlossyDetection det = detect_glossy_regions(trainer.model().view(false), trainer.views(),
                                                    RasterRenderer::settings_for(config), trainer.device(), s);
  AutoDecision d;
  d.iteration = trainer.state().iteration;
  d.glossy = det.glossy;
  d.fraction = det.fraction;
  d.threshold = s.min_fraction;
  d.covered = det.covered;
  d.scored = det.scored;
  d.detected = det.detected;
  d.planes = det.planes;
  d.backdrops = int(std::count(det.rejected_planes.begin(), det.rejected_planes.end(), true));
  d.mask_pixels = det.in_masks;
  d.mirror_world = det.by_mirror_world;
  d.mask_dir = run_dir / "detected_gloss";
  write_masks(d.mask_dir, trainer.views(), det);

  TrainConfig next = config;
  next.input.auto_detect_glossy = false;
  if (det.glossy) {
    next = lengthened_for_late_decision(next, d.iteration);
    d.extended_by = next.iterations - config.iterations;
    next.mode = TrainMode::Intrinsic;
    next.input.glossy_mask_dir = d.mask_dir.string();
    next.intrinsic.warmup = warmup_ending_at(next, d.iteration);
    trainer.switch_mode(next, make_renderer(next, trainer.extent(), trainer.device()), [&](std::vector<TrainView>& views) {
      for (size_t i = 0; i < views.size(); ++i) views[i].glossy_mask.assign(det.masks[i].begin(), det.masks[i].end());
      if (!next.intrinsic.normals.empty()) load_normal_priors(next.intrinsic.normals, views);
    });
  } else {
    trainer.switch_mode(next, trainer.renderer());
  }
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_summary(d.mask_dir, trainer.views(), det, s, d);
  write_run_config(run_dir, trainer.config());
  return d;
}

}  // namespace goris
