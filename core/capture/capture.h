#pragma once
// A capture import: a folder of photos or a video in, a data set out that `goris train` reads. COLMAP runs
// as child processes on the CPU (SIFT features, exhaustive or sequential matching, incremental mapping,
// undistortion to PINHOLE cameras); the result is COLMAP's undistorted layout, images/ + sparse/0 (+ masks/
// when a masks folder was given), with capture_report.json and capture_report.txt beside it. Everything is
// written into a temporary folder next to the output, renamed into place at the end: a failed or stopped
// capture leaves no half data set. Used by `goris capture` and by the editor's Open panel (ui/document/capture_job.h,
// a background job with progress and a stop flag).
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace goris::capture {

struct CaptureOptions {
  std::filesystem::path input;   // folder of images, or a video file
  std::filesystem::path out;     // the data set folder to create (must not exist)
  std::filesystem::path masks;   // optional: masks/<image stem>.* for the photos of a folder
  int max_images = 0;            // 0: every photo of a folder, 100 frames of a video
  int width = 0;                 // shrink the photos to this width first (0: keep)
  std::string matcher = "exhaustive";   // or "sequential" (video, ordered photos: faster)
  std::string camera_model = "SIMPLE_RADIAL";  // COLMAP camera model shared by all photos
  int max_features = 2048;       // SIFT features per image (CPU matching time grows with its square)
  std::filesystem::path colmap;  // the colmap program; empty: `colmap` on PATH
};

struct CaptureProgress {
  std::string stage;  // "frames", "features", "matching", "mapping", "undistorting"
  int stage_index = 0, stage_count = 0;
  int done = 0, total = 0;  // in the stage's units (files, blocks, registered images)
  double stage_seconds = 0;  // time in the stage so far
  double eta_s = -1;        // estimated seconds left in the stage; < 0 while unknown
};

struct StageTime {
  std::string stage;
  double seconds = 0;
};

struct CaptureReport {
  std::filesystem::path input, out;
  bool from_video = false;
  int candidates = 0;   // photos in the folder / frames in the video
  int images = 0;       // photos given to COLMAP
  int registered = 0;   // photos with a pose in the model
  int width = 0, height = 0;     // size of the photos given to COLMAP
  long long points = 0;          // 3D points of the model
  double mean_reprojection_error_px = 0;
  std::string matcher, camera_model;
  bool masks = false;
  std::vector<StageTime> stages;
  double seconds_total = 0;
};

// `requested` when given, else `colmap` on PATH; throws goris::Error naming the install command when there
// is none.
std::filesystem::path find_colmap(const std::filesystem::path& requested = {});

// Runs the whole import. Throws goris::Error naming the file and the problem: COLMAP missing, too few
// photos, an unreadable video, mapping that registered too few photos (with what to try), an output that
// exists, lies inside the input folder or would land inside a data set. `stop` (optional) ends the work
// early: the temporary folder is removed and goris::Error says so.
CaptureReport run_capture(const CaptureOptions& options, const std::function<void(const CaptureProgress&)>& on_progress = {},
                          const std::atomic<bool>* stop = nullptr);

// The report as JSON text and as a few lines for people.
std::string report_json(const CaptureReport& r);
std::string report_text(const CaptureReport& r);

}  // namespace goris::capture
