#pragma once
// Exports of a run folder (docs/user/export.md): `goris export` and the editor call these. Works on a
// stage-1 run (RUN) and a stage-2 result (RUN/removal) alike, both being run folders.
//
//   write_ply      the model in the standard 3DGS layout with the intrinsic attributes as extra properties,
//                  the 3D filter folded into scales and opacities (viewers without it show what we render);
//   write_baked    a standard SH-only 3DGS model that any viewer shows as the run's renderer does
//                  (export/distill/distill.h; for a radiance run the model itself), and OUT.json beside it
//                  with the distillation fidelity (PSNR against the run's renderer on held-out cameras:
//                  the test split, or an orbit when the data set has none), iterations and time;
//   write_model    a plain SH model (write_baked's, or a radiance run's own) as SPZ, compressed PLY, .splat or GLB
//                  for viewers and engines that read those (core/io/splat_formats.h);
//   write_renders  one PNG per frame from the run's renderer (test or train cameras, or an orbit: see
//                  export/frames/camera_path.h), contact_sheet.png with all frames and cameras.json.
//
// Every file goes through a temporary file renamed into place; check_output_* (core/io/output_path.h) run
// before any work so that an unwritable path fails in a second, not after a distillation.
#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/io/dataset.h"
#include "core/io/output_path.h"
#include "core/io/ply.h"
#include "core/scene/gaussians.h"
#include "export/distill/distill.h"
#include "render/maps/channels.h"
#include "train/config/train_config.h"
#include "train/loop/differentiable_renderer.h"

namespace goris {

enum class RenderPath { Test, Train, Orbit };
// "test", "train", "orbit"; anything else is a goris::Error listing them.
RenderPath parse_render_path(const std::string& name);
const char* render_path_name(RenderPath path);
constexpr int kDefaultOrbitFrames = 36;

struct BakedReport {
  std::filesystem::path ply, json;
  bool distilled = false;  // false: a radiance run, whose model is already plain SH
  std::string holdout;     // "test" (the data set's test cameras) or "orbit"
  DistillResult distill;   // radiance runs: iterations 0, PSNRs of the baked PLY against the model's renders
  // Against the data set's test images (NaN without test views): the run's renderer and the baked model.
  double gt_psnr_run = 0, gt_psnr_baked = 0;
  DistillSettings settings;              // as used (a radiance run: 0 iterations)
  std::pair<int, int> resolution{0, 0};  // of the held-out views
};

struct RendersReport {
  std::filesystem::path dir, contact_sheet;
  std::vector<std::string> frames;  // file names, in order
  int width = 0, height = 0;
  double ms_per_frame = 0;
};

class RunExport {
 public:
  // Loads the run's configuration, its data set's cameras (not the images), its model and its renderer
  // (intrinsic runs: shading on). `data`: the data set's folder when it moved after training (--data,
  // train/run/run_data.h; empty = config.json's). Throws goris::Error naming the file for a missing or
  // broken run folder.
  RunExport(const std::filesystem::path& run_dir, Device device, const std::string& data = {});

  const std::filesystem::path& run_dir() const { return run_dir_; }
  const TrainConfig& config() const { return config_; }
  bool intrinsic() const { return config_.mode == TrainMode::Intrinsic; }
  const GaussianModel& model() const { return model_; }
  const std::string& model_source() const { return model_source_; }
  const Dataset& dataset() const { return dataset_; }
  Device device() const { return device_; }

  // The run's renderer's colour from `camera`: planar RGB [3][H][W] on the host (not clamped).
  std::vector<float> render(const Camera& camera);
  // One channel of that view as a viewable planar RGB image in [0, 1] (export/frames/channel_image.h);
  // Channel::Final is render() clamped. Throws goris::Error naming the run when it cannot show the channel.
  std::vector<float> render(const Camera& camera, Channel channel);
  // Null when the run's renderer can show `channel` along a camera path; else why not.
  const char* channel_unavailable(Channel channel) const;
  // Throws goris::Error naming the run and the channel when channel_unavailable() says why not.
  void require_channel(Channel channel) const;

  void write_ply(const std::filesystem::path& out) const;
  BakedReport write_baked(const std::filesystem::path& out, const DistillSettings& settings,
                          const std::function<void(const DistillProgress&)>& on_progress = {},
                          const std::atomic<bool>* stop = nullptr);
  // write_baked in two steps: the distillation (report.distill.ply is the baked model), then OUT.ply and
  // OUT.json (sets report.ply and report.json).
  BakedReport bake(const DistillSettings& settings, const std::function<void(const DistillProgress&)>& on_progress = {},
                   const std::atomic<bool>* stop = nullptr);
  void write_baked_files(BakedReport& report, const std::filesystem::path& out) const;
  // A radiance run's model as plain SH for the standard formats: the 3D filter baked in, no extra
  // properties (what write_baked bakes for such a run). Throws for an intrinsic run, whose colours need bake().
  GaussianPly radiance_model() const;
  // Writes a plain SH model in the format out's name says: .spz, .compressed.ply, .splat, .glb or .ply
  // (core/io/splat_formats.h), through a temporary file.
  void write_model(const std::filesystem::path& out, const GaussianPly& model) const;
  // frames: orbit frame count (0 = kDefaultOrbitFrames), or for test / train an evenly spaced subset of
  // that many views (0 = all). on_frame(done, total) reports progress.
  RendersReport write_renders(const std::filesystem::path& dir, RenderPath path, int frames,
                              const std::function<void(size_t, size_t)>& on_frame = {},
                              Channel channel = Channel::Final);

  // The cameras a render path visits (names beside them), at the run's resolution.
  std::vector<Camera> path_cameras(RenderPath path, int frames, std::vector<std::string>* names = nullptr) const;

 private:
  std::filesystem::path run_dir_;
  Device device_;
  TrainConfig config_;
  Dataset dataset_;
  float extent_ = 1.0f;
  GaussianModel model_;
  std::string model_source_;
  std::shared_ptr<DifferentiableRenderer> renderer_;
};

// OUT.json beside a baked OUT.ply (the extension replaced).
std::filesystem::path baked_json_path(const std::filesystem::path& ply);

}  // namespace goris
