#include "export/distill/distill.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/compute/memory.h"
#include "core/util/error.h"
#include "export/frames/camera_path.h"
#include "train/loop/trainer.h"
#include "train/losses/image_losses.h"
#include "train/radiance/raster_renderer.h"

namespace goris {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The teacher's image from `cam`, checked and clamped to what a saved image shows.
std::vector<float> target_image(const DistillTeacher& teacher, const Camera& cam, const std::string& what) {
  std::vector<float> img = teacher(cam);
  const size_t n = size_t(3) * size_t(cam.width) * size_t(cam.height);
  if (img.size() != n)
    throw Error("distillation", "the teacher's image from " + what + " has " + std::to_string(img.size()) +
                                    " values, expected " + std::to_string(n) + " (3 x " + std::to_string(cam.width) +
                                    " x " + std::to_string(cam.height) + ")");
  for (float& v : img) {
    if (!std::isfinite(v)) throw Error("distillation", "the teacher's image from " + what + " has non-finite values");
    v = std::clamp(v, 0.0f, 1.0f);
  }
  return img;
}

// The start's parameters as the student begins with them: optimiser moments cleared (a fresh optimiser),
// SH degree 3 with the coefficients the start never rendered set to zero (so the student renders like it).
GaussianModel student_from(const GaussianModel& start) {
  GaussianModel m = start.copy_to(start.device());
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    t.grad.fill_zero();
    t.adam_m.fill_zero();
    t.adam_v.fill_zero();
  }
  const int used = (std::clamp(start.sh_degree, 0, 3) + 1) * (std::clamp(start.sh_degree, 0, 3) + 1);
  if (used < kMaxShCoeffs) {
    ParamTensor& sh = m.tensor(Param::Sh);
    std::vector<float> v = sh.value.to_host();
    for (size_t i = 0; i < m.count(); ++i)
      std::fill(v.begin() + std::ptrdiff_t(i * kMaxShCoeffs * 3 + size_t(used) * 3),
                v.begin() + std::ptrdiff_t((i + 1) * kMaxShCoeffs * 3), 0.0f);
    sh.value.upload(v.data(), v.size());
  }
  m.sh_degree = 3;
  m.max_sh_degree = 3;
  return m;
}

}  // namespace

TrainConfig distill_config(const TrainConfig& run_config, const DistillSettings& s) {
  TrainConfig c = run_config;
  c.mode = TrainMode::Radiance;
  c.iterations = std::max(1, s.iterations);  // a valid configuration even when nothing is trained
  c.seed = s.seed;
  c.sh.max_degree = 3;
  c.densify.until_iter = 0;      // no densification, no opacity reset
  c.anti_aliasing.filter_3d = false;  // keep the start's 3D filter as it is
  c.loss.depth_normal_weight = 0.0f;  // colour loss only (S1.6)
  const float g = s.geometry_lr_scale;
  c.lr.position_init *= g;
  c.lr.position_final *= g;
  c.lr.scale *= g;
  c.lr.rotation *= g;
  c.lr.opacity *= g;
  c.lr.sh_dc *= s.sh_lr_scale;
  c.lr.sh_rest *= s.sh_lr_scale;
  c.bookkeeping.checkpoint_interval = 0;
  return c;
}

GaussianPly baked_sh_ply(const GaussianModel& model) {
  GaussianPly ply = model.to_ply(/*bake_3d_filter=*/true);
  ply.extras.clear();
  return ply;
}

double raster_psnr(GaussianModel& model, const TrainConfig& config, const std::vector<Camera>& cameras,
                   const std::vector<std::vector<float>>& targets, std::vector<double>* per_view) {
  if (targets.size() != cameras.size()) throw Error("PSNR", "one target image per camera is needed");
  if (cameras.empty()) throw Error("PSNR", "no cameras");
  RasterRenderer renderer(RasterRenderer::settings_for(config), model.device());
  double sum = 0;
  if (per_view) per_view->clear();
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Camera& cam = cameras[i];
    const size_t n = size_t(3) * size_t(cam.width) * size_t(cam.height);
    if (targets[i].size() != n) throw Error("PSNR", "target " + std::to_string(i) + " does not match its camera's size");
    const RenderedImages r = renderer.forward(model.view(false), cam);
    std::vector<float> img(n);
    device_copy(img.data(), Device::CPU, r.color, model.device(), n * sizeof(float));
    for (float& v : img) v = std::clamp(v, 0.0f, 1.0f);
    const double p = psnr_from_mse(mse<float>(img.data(), targets[i].data(), n));
    if (per_view) per_view->push_back(p);
    sum += p;
  }
  return sum / double(cameras.size());
}

DistillResult distill_to_sh(const GaussianModel& start, const DistillTeacher& teacher, const TrainConfig& run_config,
                            const std::vector<Camera>& train_cameras, const std::vector<Camera>& holdout_cameras,
                            float extent, const DistillSettings& s,
                            const std::function<void(const DistillProgress&)>& on_progress,
                            const std::atomic<bool>* stop) {
  if (train_cameras.empty()) throw Error("distillation", "no training cameras to render targets from");
  if (holdout_cameras.empty()) throw Error("distillation", "no held-out cameras to measure the fidelity on");
  if (s.iterations < 0) throw Error("distillation", "the number of iterations must be >= 0");
  if (!(s.geometry_lr_scale >= 0) || !std::isfinite(s.geometry_lr_scale))
    throw Error("distillation", "the geometry learning-rate scale must be finite and >= 0");
  if (!(s.sh_lr_scale > 0) || !std::isfinite(s.sh_lr_scale))
    throw Error("distillation", "the SH learning-rate scale must be finite and > 0");
  if (start.count() == 0) throw Error("distillation", "the model has no Gaussians");
  const auto t_total = Clock::now();
  auto report = [&](const DistillProgress& p) {
    if (on_progress) on_progress(p);
  };
  DistillResult out;

  // Targets: training cameras, interpolated cameras, then the held-out ones (only those without training).
  const bool train_any = s.iterations > 0;
  const int extra = !train_any ? 0 : s.extra_views < 0 ? int(train_cameras.size()) : s.extra_views;
  const std::vector<Camera> between = interpolated_cameras(train_cameras, extra, s.seed);
  const size_t n_targets = train_any ? train_cameras.size() + between.size() : 0;
  const size_t n_total = n_targets + holdout_cameras.size();
  std::vector<TrainView> views;
  views.reserve(n_targets);
  auto t0 = Clock::now();
  for (size_t i = 0; i < n_total; ++i) {
    const bool held = i >= n_targets, train = !held && i < train_cameras.size();
    const Camera& cam = train ? train_cameras[i] : held ? holdout_cameras[i - n_targets] : between[i - train_cameras.size()];
    const std::string name = train ? "training camera " + std::to_string(i)
                             : held ? "held-out camera " + std::to_string(i - n_targets)
                                    : "interpolated camera " + std::to_string(i - train_cameras.size());
    std::vector<float> img = target_image(teacher, cam, name);
    if (held) {
      out.holdout_images.push_back(std::move(img));
    } else {
      TrainView v;
      v.name = name;
      v.camera = cam;
      v.image = std::move(img);
      views.push_back(std::move(v));
    }
    report({"targets", int(i + 1), int(n_total)});
  }
  out.seconds_targets = seconds_since(t0);
  out.target_views = n_targets;
  out.extra_views = between.size();
  out.holdout_views = holdout_cameras.size();

  const TrainConfig config = distill_config(run_config, s);
  TrainerState state;
  state.model = student_from(start);
  state.rng.seed(s.seed);
  out.psnr_start = raster_psnr(state.model, config, holdout_cameras, out.holdout_images);

  if (train_any) {
    t0 = Clock::now();
    auto renderer = std::make_shared<RasterRenderer>(RasterRenderer::settings_for(config), start.device());
    Trainer trainer(config, std::move(views), extent, renderer, std::move(state));
    Trainer::RunOptions ro;
    ro.stop = stop;
    ro.progress_every = std::max(1, s.progress_every);
    ro.on_progress = [&](const TrainProgress& p) {
      report({"distilling", p.iteration, p.total, p.loss, p.psnr, p.it_per_s, p.eta_s});
    };
    out.stopped = trainer.run(ro) == Trainer::RunResult::Stopped;
    out.iterations = trainer.state().iteration;
    out.seconds_train = seconds_since(t0);
    out.ply = baked_sh_ply(trainer.model());
  } else {
    out.ply = baked_sh_ply(state.model);
  }

  // Fidelity of exactly what is written: the PLY read back (3D filter folded in) through the rasterizer.
  t0 = Clock::now();
  GaussianModel baked = GaussianModel::from_ply(out.ply, start.device());
  out.psnr = raster_psnr(baked, config, holdout_cameras, out.holdout_images, &out.psnr_per_view);
  out.seconds_holdout = seconds_since(t0);
  report({"held-out views", int(holdout_cameras.size()), int(holdout_cameras.size())});
  out.seconds_total = seconds_since(t_total);
  return out;
}

}  // namespace goris
