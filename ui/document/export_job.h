#pragma once
// The exports of a run folder (`goris export`: export/run/run_export.h) on a background job
// (ui/document/background_job.h) for the editor's Export dialog and the scripted mode's `export` actions: the
// intrinsic PLY, the baked (distilled, SH-only) PLY (and the same model as SPZ, compressed PLY, .splat, GLB)
// and rendered frames, in that order, each through the same library call as the CLI.
//
// Every output path is checked before any work starts (an unwritable path fails in a second, not after a
// distillation). Files go through a temporary file renamed into place, so a file is either the old one or
// complete. A cancel stops at the next progress report (each distillation iteration, each rendered view)
// and writes nothing more: the parts finished before it stay. finish_early() instead ends the distillation
// at once and writes the baked model so far (marked "stopped" in its json), as Ctrl-C does in the CLI.
// The GUI polls progress() and never waits.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/compute/device_choice.h"
#include "core/io/splat_formats.h"
#include "export/run/run_export.h"
#include "ui/document/background_job.h"

namespace goris::ui {

// What one export writes (the dialog's Export button and a script line both build one of these).
struct ExportRequest {
  std::filesystem::path run_dir;  // a run folder: RUN or a stage-2 result RUN/removal
  std::filesystem::path ply;      // the model with its intrinsic attributes (empty: not wanted)
  std::filesystem::path baked;    // the distilled SH-only model, OUT.json beside it (empty: not wanted)
  int baked_iterations = 2000;    // distillation iterations (a radiance run needs none: baked as it is)
  // The baked model also in these formats (SPZ, compressed PLY, .splat, GLB), beside the baked PLY under the
  // same name (baked_format_path); needs `baked`.
  std::vector<SplatFormat> baked_formats;
  std::filesystem::path renders;  // a folder of PNG frames, contact_sheet.png, cameras.json (empty: none)
  RenderPath render_path = RenderPath::Test;
  int frames = 0;               // orbit: frame count (0 = 36); test / train: evenly spaced views (0 = all)
  DeviceChoice device = DeviceChoice::Auto;
};

// Where the baked model goes in `format`: baked's folder and stem with the format's extension
// (export/baked.ply -> export/baked.spz, export/baked.compressed.ply, export/baked.splat, export/baked.glb).
std::filesystem::path baked_format_path(const std::filesystem::path& baked, SplatFormat format);

// Throws goris::Error for a request that cannot run: no run folder, nothing wanted, the two PLYs being one
// file, a non-positive iteration count, a negative frame count or other formats without the baked PLY.
void check_export_request(const ExportRequest& request);

enum class ExportPart { Load, Ply, Baked, Renders };
constexpr int kExportPartCount = 4;
const char* export_part_name(ExportPart p);  // "load the run", "intrinsic PLY", "baked PLY", "renders"

struct ExportPartStatus {
  bool wanted = false, started = false, complete = false;
  double fraction = 0;         // 0..1 of this part
  std::string detail;          // e.g. "distilling 120/400, PSNR 27.1 dB, ETA 12s"
  std::filesystem::path path;  // where it goes
  double seconds = 0;          // time spent on it
};

struct ExportProgress {
  std::array<ExportPartStatus, kExportPartCount> parts;
  int current = -1;  // the part being worked on (-1: none yet)
  // The whole export, 0..1: parts weighted by their expected cost.
  double fraction() const;
  // A part's expected cost in units of one render by the run's renderer (a distillation iteration costs
  // about as much), from the counts below.
  double weight(ExportPart p) const;
  // The baked part's share spent rendering the distillation's target and held-out views.
  double baked_render_share() const;
  int baked_iterations = 0;  // distillation iterations (0: a radiance run, baked as it is)
  int teacher_views = 0;     // views the distillation renders with the run's renderer (estimated until known)
  int frames = 0;            // renders
};

// What a finished (or cancelled) export wrote.
struct ExportResult {
  std::vector<std::filesystem::path> written;  // every file / folder written, in order
  std::optional<BakedReport> baked;            // without distill.ply and distill.holdout_images (kept small)
  std::optional<RendersReport> renders;
  std::string summary;  // one line per part
};

class ExportJob : public JobReadout {
 public:
  ExportJob() : JobReadout(job_) {}
  // Checks the request (check_export_request) and starts the worker. Throws goris::Error while one runs.
  void start(const ExportRequest& request);
  void cancel();            // Running -> Cancelling; otherwise nothing
  void finish_early();      // ends the distillation now and writes what it has; otherwise nothing
  bool distilling() const;  // the distillation's training loop runs (finish_early has an effect)

  // status(): what the worker does, how it ended, or why it failed ("baked PLY: FILE: problem").
  ExportProgress progress() const { return progress_.get(); }
  ExportResult result() const { return result_.get(); }     // what was written (complete once the export ended)
  ExportRequest request() const { return request_.get(); }  // of the last start

 private:
  std::string work(const ExportRequest& request);
  // Worker side: marks part `p` as the current one / updates it; throws the cancellation when asked to stop.
  void begin_part(ExportPart p);
  void update_part(ExportPart p, double fraction, const std::string& detail);
  void end_part(ExportPart p, const std::string& detail);
  void check_cancel() const;

  Guarded<ExportProgress> progress_;
  Guarded<ExportResult> result_;
  Guarded<ExportRequest> request_;
  std::chrono::steady_clock::time_point part_started_{};  // worker only
  std::atomic<bool> distilling_{false};
  std::atomic<bool> stop_distill_{false};
  // Last: joined before the members its work uses go. The work ends a cancelled export itself (what it kept).
  BackgroundJob job_{"export", BackgroundJob::StopRule::WorkDecides};
};

}  // namespace goris::ui
