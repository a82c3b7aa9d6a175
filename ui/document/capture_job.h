#pragma once
// The editor's capture import (the Open panel's "Import photos / video", the script's `import_capture`):
// the same library call as `goris capture` (core/capture/capture.h run_capture) on a background job
// (ui/document/background_job.h), with the progress of each stage for the panel. Cancelling raises run_capture's
// stop flag: COLMAP's child process is stopped and the temporary folder removed, so nothing is written.
#include <array>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

#include "core/capture/capture.h"
#include "ui/document/background_job.h"

namespace goris::ui {

// The stages run_capture reports, in order (CaptureProgress::stage_index 1..5).
constexpr int kCaptureStageCount = 5;
const char* capture_stage_name(int index);  // 0-based: "frames", "features", ...

struct CaptureStageStatus {
  int done = 0, total = 0;
  double seconds = 0;
  double eta_s = -1;  // < 0 while unknown
  bool started = false, complete = false;
  float fraction() const { return complete ? 1.0f : total > 0 ? float(done) / float(total) : 0.0f; }
};

struct CaptureJobProgress {
  std::array<CaptureStageStatus, kCaptureStageCount> stages{};
  int current = -1;  // 0-based stage being worked on; -1 before the first report
};

// Whether the editor offers to import `path`: a video file (by its extension), or a folder with photos
// that holds no data set the loaders recognise.
bool is_capture_input(const std::filesystem::path& path);

// Where an import of `input` goes unless the user says otherwise: beside it, INPUT_NAME_data (with a
// number added while that exists).
std::filesystem::path default_capture_output(const std::filesystem::path& input);

class CaptureJob : public JobReadout {
 public:
  CaptureJob() : JobReadout(job_) {}
  // Starts run_capture(options). Throws goris::Error while an import runs.
  void start(const capture::CaptureOptions& options);
  void cancel();

  CaptureJobProgress progress() const;
  capture::CaptureOptions options() const;               // of the last start
  std::optional<capture::CaptureReport> report() const;  // of the last import that finished

 private:
  void on_progress(const capture::CaptureProgress& p);

  mutable std::mutex mutex_;
  CaptureJobProgress progress_;
  capture::CaptureOptions options_;
  std::optional<capture::CaptureReport> report_;
  BackgroundJob job_{"import"};  // last: joined before the members its work uses go
};

}  // namespace goris::ui
