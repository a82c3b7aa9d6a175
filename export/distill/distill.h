#pragma once
// Distillation of a renderer's appearance into plain SH colours (paper S1.6, "Ours-distill"): the result is a
// standard 3DGS model that any viewer shows as the engine's renderer does, e.g. the shaded colour
// C = D + (1 - M) G of an intrinsic run, which needs tracing, baked into view-dependent SH.
//
//   targets   the teacher's images from the training cameras plus `extra_views` cameras interpolated
//             between them (export/frames/camera_path.h), so that view dependence is sampled densely
//             between the training viewpoints; clamped to [0, 1] (what a saved image shows);
//   student   a copy of the starting Gaussians in radiance mode at SH degree 3 (higher coefficients the
//             start did not use begin at zero), trained by the Trainer with the rasterizer: colour loss only,
//             no densification, no 3D-filter recomputation (the start's filter is kept), SH learning rates
//             of the run, position / scale / rotation / opacity rates x geometry_lr_scale (0 = frozen, so
//             the geometry is exactly the start's);
//   fidelity  PSNR of the baked model (the PLY as written, re-read, rendered by the rasterizer) against the
//             teacher's images from held-out cameras, and the same for the start (before distillation).
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/io/camera.h"
#include "core/io/ply.h"
#include "core/scene/gaussians.h"
#include "train/config/train_config.h"

namespace goris {

// The image to reproduce from a camera: planar RGB [3][H][W] on the host at the camera's size.
using DistillTeacher = std::function<std::vector<float>(const Camera&)>;

struct DistillSettings {
  int iterations = 2000;           // 0 = no training: the start baked as it is (radiance runs)
  int extra_views = -1;            // interpolated cameras; -1 = as many as the training cameras
  float geometry_lr_scale = 0.0f;  // x the run's position / scale / rotation / opacity rates (0 = frozen)
  // x the run's SH rates. The run's rates suit 30K iterations of joint training; distillation fits colour
  // alone on frozen geometry and must move far from the start (SH that rendered D, not C): at x1 a few
  // hundred iterations barely move, x20 is where the fidelity stops rising (docs/lab/bench/NOTES.md,
  // 2026-11-21, "baked export").
  float sh_lr_scale = 20.0f;
  std::uint64_t seed = 0;          // view order and interpolated cameras
  int progress_every = 10;         // training iterations between progress reports
};

struct DistillProgress {
  std::string phase;  // "targets" (rendering the teacher), "distilling", "held-out views"
  int done = 0, total = 0;
  double loss = 0, psnr = 0;  // distilling: smoothed training loss / PSNR against the targets
  double it_per_s = 0, eta_s = 0;
};

struct DistillResult {
  GaussianPly ply;           // the baked model: standard layout, SH degree 3, 3D filter folded in, no extras
  double psnr_start = 0;     // held-out PSNR (dB, mean over views) of the start's SH colour vs the teacher
  double psnr = 0;           // the same for the baked model
  std::vector<double> psnr_per_view;  // the baked model, per held-out camera
  std::vector<std::vector<float>> holdout_images;  // the teacher's (clamped) images from the held-out cameras
  size_t target_views = 0, extra_views = 0, holdout_views = 0;
  int iterations = 0;        // completed (fewer when stopped)
  bool stopped = false;
  double seconds_targets = 0, seconds_train = 0, seconds_holdout = 0, seconds_total = 0;
};

// Distils `teacher` into SH on a copy of `start` (on the start's device). `run_config` supplies the
// rasterizer settings (background, 2D filter), the loss and the SH learning rates; `extent` the scene size.
// Throws goris::Error for no training or held-out cameras, negative iterations, a teacher image of the wrong
// size or non-finite values. `stop` (optional) ends training early; the result is still complete.
DistillResult distill_to_sh(const GaussianModel& start, const DistillTeacher& teacher, const TrainConfig& run_config,
                            const std::vector<Camera>& train_cameras, const std::vector<Camera>& holdout_cameras,
                            float extent, const DistillSettings& settings,
                            const std::function<void(const DistillProgress&)>& on_progress = {},
                            const std::atomic<bool>* stop = nullptr);

// The configuration the student trains with (see the header comment).
TrainConfig distill_config(const TrainConfig& run_config, const DistillSettings& settings);

// A standard SH-only PLY of a model: to_ply(bake_3d_filter = true) without the extra properties.
GaussianPly baked_sh_ply(const GaussianModel& model);

// Mean over views of the PSNR (dB) of the model rasterized with `config`'s settings (clamped to [0, 1])
// against `targets` (planar RGB, one per camera). `per_view` (optional) receives each view's PSNR.
double raster_psnr(GaussianModel& model, const TrainConfig& config, const std::vector<Camera>& cameras,
                   const std::vector<std::vector<float>>& targets, std::vector<double>* per_view = nullptr);

}  // namespace goris
