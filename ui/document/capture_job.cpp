#include "ui/document/capture_job.h"

#include <system_error>

#include "core/capture/capture_frames.h"
#include "core/io/dataset.h"
#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;

const char* capture_stage_name(int index) {
  static constexpr const char* kNames[kCaptureStageCount] = {"frames", "features", "matching", "mapping",
                                                             "undistorting"};
  return index >= 0 && index < kCaptureStageCount ? kNames[index] : "?";
}

bool is_capture_input(const fs::path& path) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return capture::is_video_file(path);
  if (!fs::is_directory(path, ec)) return false;
  try {
    detect_dataset_format(path);
    return false;  // a data set: opened, not imported
  } catch (const Error&) {
  }
  try {
    return !capture::list_image_files(path).empty();
  } catch (const Error&) {
    return false;
  }
}

fs::path default_capture_output(const fs::path& input) {
  fs::path in = fs::absolute(input).lexically_normal();
  if (in.filename().empty()) in = in.parent_path();
  const std::string base = in.stem().string() + "_data";
  fs::path out = in.parent_path() / base;
  std::error_code ec;
  for (int k = 2; fs::exists(out, ec) && k < 1000; ++k) out = in.parent_path() / (base + "_" + std::to_string(k));
  return out;
}

void CaptureJob::start(const capture::CaptureOptions& options) {
  if (job_.active()) throw Error("import: an import is running: wait for it or cancel it first");
  {
    std::lock_guard lk(mutex_);
    options_ = options;
    progress_ = CaptureJobProgress();
    report_.reset();
  }
  job_.start(
      [this, options](const std::atomic<bool>& stop) {
        const capture::CaptureReport r =
            capture::run_capture(options, [this](const capture::CaptureProgress& p) { on_progress(p); }, &stop);
        {
          std::lock_guard lk(mutex_);
          report_ = r;
          for (CaptureStageStatus& s : progress_.stages)
            if (s.started) s.complete = true;
        }
        return "imported " + r.out.string() + ": " + std::to_string(r.registered) + " of " + std::to_string(r.images) +
               " photos registered";
      },
      "checking " + options.input.string());
}

void CaptureJob::cancel() {
  job_.set_cancelled_status("cancelled: COLMAP stopped, nothing was written");
  job_.cancel("cancelling: stopping COLMAP");
}

void CaptureJob::on_progress(const capture::CaptureProgress& p) {
  const int k = p.stage_index - 1;
  // The model's statistics run as a short step of the mapping stage under their own name: not a stage here.
  if (k < 0 || k >= kCaptureStageCount || p.stage != capture_stage_name(k)) return;
  {
    std::lock_guard lk(mutex_);
    for (int i = 0; i < k; ++i)
      if (progress_.stages[size_t(i)].started) progress_.stages[size_t(i)].complete = true;
    CaptureStageStatus& s = progress_.stages[size_t(k)];
    s.started = true;
    s.done = p.done;
    s.total = p.total;
    s.seconds = p.stage_seconds;
    s.eta_s = p.eta_s;
    progress_.current = k;
  }
  std::string line = "[" + std::to_string(p.stage_index) + "/" + std::to_string(p.stage_count) + "] " + p.stage;
  if (p.total > 0) line += " " + std::to_string(p.done) + "/" + std::to_string(p.total);
  job_.set_status(line);
}

CaptureJobProgress CaptureJob::progress() const {
  std::lock_guard lk(mutex_);
  return progress_;
}

capture::CaptureOptions CaptureJob::options() const {
  std::lock_guard lk(mutex_);
  return options_;
}

std::optional<capture::CaptureReport> CaptureJob::report() const {
  std::lock_guard lk(mutex_);
  return report_;
}

}  // namespace goris::ui
