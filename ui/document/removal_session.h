#pragma once
// Stage 2 (object removal, removal/pipeline/removal_pipeline.h run_removal) on a background job
// (ui/document/background_job.h) for the editor, on the same run folder as `goris remove`. A new start after a run
// ended resumes from what RUN/removal holds.
//
// The GUI polls progress() (per step, overall, ETA) and never waits. Cancelling raises the pipeline's stop
// flag: it leaves the run folder consistent (finished steps' files, the fine-tune's checkpoint) and a later
// start resumes.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "removal/pipeline/removal_pipeline.h"
#include "ui/document/background_job.h"
#include "ui/document/removal_progress.h"

namespace goris::ui {

class RemovalSession : public JobReadout {
 public:
  RemovalSession() : JobReadout(job_) {}
  // Starts run_removal(run_dir, options) on the worker. Throws goris::Error while one runs.
  void start(const std::filesystem::path& run_dir, const RemovalOptions& options);
  void cancel();  // Running -> Cancelling; otherwise nothing
  // The removal's own 2D inpainter (RemovalOptions::inpainter): what the settings' "" stands for.
  static std::string default_inpainter() { return RemovalOptions{}.inpainter; }

  RemovalProgressTracker progress() const { return progress_.get(); }
  // Of the last run that returned (finished or cancelled).
  std::optional<RemovalReport> report() const { return report_.get(); }
  std::filesystem::path run_dir() const { return run_dir_.get(); }

 private:
  std::string work(const std::filesystem::path& run_dir, const RemovalOptions& options,
                   const std::atomic<bool>& stop);

  Guarded<RemovalProgressTracker> progress_;
  Guarded<std::optional<RemovalReport>> report_;
  Guarded<std::filesystem::path> run_dir_;
  BackgroundJob job_{"remove"};  // last: joined before the members its work uses go
};

}  // namespace goris::ui
