// `goris detect RUN [--checkpoint FILE] [--device D] [--out DIR] [--set KEY=VALUE ...]`: what `--mode auto`
// would decide on a trained model - the glossy-region detection from the photos
// (train/setup/glossy_detection.h) on the run's latest (or a given) checkpoint, with the run's detection
// settings or others given with --set. Prints the evidence, the planes and the decision, and the agreement
// with the data set's own glossy masks when it has them; --out writes the masks (gloss_<view>.png).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_common/command.h"
#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/util/error.h"
#include "core/scene/plane_from_masks.h"
#include "train/loop/checkpoint.h"
#include "train/radiance/raster_renderer.h"
#include "train/run/train_setup.h"
#include "train/setup/glossy_detection.h"
#include "train/setup/training_setup.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, checkpoint, device = "auto", out;
  std::vector<std::string> sets;  // detection settings to try (intrinsic_detect_*)
};

void run_detect(const Options& o) {
  fs::path ck = o.checkpoint;
  if (ck.empty()) {
    const auto latest = latest_checkpoint(o.run);
    if (!latest) throw Error(o.run, "has no checkpoint (RUN/checkpoints/iter_*.ckpt); train with --checkpoint-every");
    ck = *latest;
  }
  const Device device = resolve_device(o.device);
  Checkpoint c = read_checkpoint(ck, device);
  TrainConfig config = c.config;
  config.input.use_glossy_masks = true;  // the data set's own masks, when it has them, are the reference
  config.input.glossy_mask_dir.clear();
  apply_config_overrides(o.sets, config);
  Dataset ds = load_dataset(config.input.data, dataset_options(config));
  select_training_data(config, ds);
  const std::vector<TrainView> views = load_train_views(ds.train, dataset_options(config));
  const GlossyDetectionSettings s = GlossyDetectionSettings::from_config(config);
  const GlossyDetection det = detect_glossy_regions(c.state.model.view(false), views,
                                                    RasterRenderer::settings_for(config), device, s);
  std::printf("%s (iteration %d): %.2f %% of the covered pixels look view-dependent (threshold %.2f %%), "
              "%zu detected of %zu scored, %d plane(s) (grown over %zu pixels on them, %zu seen behind them), "
              "masks %zu pixels -> %s\n",
              ck.c_str(), c.state.iteration, 100.0 * det.fraction, 100.0 * s.min_fraction, det.detected, det.scored,
              det.planes, det.on_planes, det.behind_planes, det.in_masks, det.glossy ? "intrinsic" : "radiance");
  std::printf("%s%s\n", det.mirror_world.summary.c_str(), det.by_mirror_world ? " (decides: intrinsic)" : "");
  // Each plane's tilt from the cameras' mean up: a table or floor is near 0 (or 180), a wall or mirror near 90.
  const glm::dvec3 up = mean_camera_up(cameras_of(views));
  for (std::size_t k = 0; k < det.plane_normals.size(); ++k) {
    const double c = std::clamp(std::abs(glm::dot(up, glm::dvec3(det.plane_normals[k]))), 0.0, 1.0);
    std::printf("plane %zu: %.1f degrees from level (the cameras' mean up)\n", k + 1, glm::degrees(std::acos(c)));
  }
  for (std::size_t k = 0; k < det.plane_in_front.size(); ++k)
    std::printf("plane fit %zu: %.1f %% of its detections stand in front of its surface (at most %.0f %%)%s\n", k + 1,
                100.0 * det.plane_in_front[k], 100.0 * s.plane_max_in_front,
                det.rejected_planes[k] ? ": not a reflector, not grown over" : "");
  MaskAgreement all;
  for (size_t i = 0; i < views.size(); ++i) {
    if (views[i].glossy_mask.size() != det.masks[i].size()) continue;
    const MaskAgreement a = compare_masks(det.masks[i], views[i].glossy_mask);
    all.detected += a.detected, all.reference += a.reference, all.both += a.both;
  }
  if (all.reference > 0)
    std::printf("against the data set's glossy masks: IoU %.3f, recall %.3f, precision %.3f\n", all.iou(), all.recall(),
                all.precision());
  if (!o.out.empty()) {
    fs::create_directories(o.out);
    for (size_t i = 0; i < views.size(); ++i) {
      Image m(views[i].camera.width, views[i].camera.height, 1);
      for (size_t p = 0; p < det.masks[i].size(); ++p) m.pixels[p] = float(det.masks[i][p]);
      save_png(fs::path(o.out) / ("gloss_" + views[i].name + ".png"), m);
      // The score at the working size: black = explained or not scored, white = 4x the threshold.
      const int sw = det.score_widths[i];
      Image sc(sw, int(det.scores[i].size()) / sw, 1);
      for (size_t p = 0; p < sc.pixels.size(); ++p)
        sc.pixels[p] = std::clamp(det.scores[i][p] / (4.0f * std::max(s.threshold, 1e-6f)), 0.0f, 1.0f);
      save_png(fs::path(o.out) / ("score_" + views[i].name + ".png"), sc);
    }
    std::printf("wrote %zu masks and scores (score_<view>.png, white = 4x the threshold) to %s\n", views.size(),
                o.out.c_str());
  }
}

void setup_detect(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("detect", "What --mode auto would decide on a trained run: glossy regions from the photos");
  c->add_option("run", o->run, "A run folder with checkpoints")->required();
  c->add_option("--checkpoint", o->checkpoint, "A checkpoint file (default: the run's latest)");
  cli::add_device_option(*c, o->device);
  c->add_option("--out", o->out, "Write the detected masks (gloss_<view>.png) here");
  c->add_option("--set", o->sets, "KEY=VALUE: another detection setting to try (intrinsic_detect_*), repeatable");
  c->callback([o] { run_detect(*o); });
}

}  // namespace
GORIS_COMMAND(47, setup_detect);
