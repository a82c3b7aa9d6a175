// `goris capture INPUT --out DATA [--max-images N] [--resolution W] [--matcher exhaustive|sequential]
// [--masks DIR] [--camera-model M] [--features N] [--colmap PATH] [--compare-to GIVEN]`: a folder of photos
// or a video to a data set through COLMAP (core/capture/capture.h), with a progress bar per stage. With
// --compare-to, the capture's camera centres are aligned to the poses of a data set of the same photos and
// the distances printed and added to the report. SIGINT, SIGTERM or SIGHUP stop COLMAP, remove the
// temporary folder and exit 130, 143 or 129.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "app/cli_common/stop_signals.h"
#include "core/capture/capture.h"
#include "core/capture/pose_alignment.h"
#include "core/io/dataset.h"
#include "core/util/error.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  capture::CaptureOptions capture;
  std::string compare_to;
};

// One line per stage: a bar redrawn in place on a terminal, a line per tenth otherwise.
class ProgressPrinter {
 public:
  void operator()(const capture::CaptureProgress& p) {
    if (p.stage != stage_) {
      if (!stage_.empty() && tty_) std::fprintf(stderr, "\n");
      stage_ = p.stage;
      tenth_ = -1;
    }
    const int tenth = p.total > 0 ? 10 * p.done / p.total : 0;
    if (!tty_ && tenth == tenth_) return;
    tenth_ = tenth;
    char bar[21];
    const int filled = p.total > 0 ? 20 * p.done / p.total : 0;
    for (int i = 0; i < 20; ++i) bar[i] = i < filled ? '#' : '.';
    bar[20] = 0;
    char eta[32] = "";
    if (p.eta_s >= 0) std::snprintf(eta, sizeof eta, "  ETA %.0f s", p.eta_s);
    std::fprintf(stderr, "%s[%d/%d] %-12s [%s] %d/%d  %.0f s%s%s", tty_ ? "\r" : "", p.stage_index, p.stage_count,
                 p.stage.c_str(), bar, p.done, p.total, p.stage_seconds, eta, tty_ ? "   " : "\n");
  }
  void finish() {
    if (!stage_.empty() && tty_) std::fprintf(stderr, "\n");
  }

 private:
  bool tty_ = isatty(STDERR_FILENO);
  std::string stage_;
  int tenth_ = -1;
};

void run_capture_command(Options& o) {
  // The data set to compare with must load before an hour of COLMAP.
  std::optional<Dataset> given;
  DatasetOptions all_views;
  all_views.test_every = 0;
  if (!o.compare_to.empty()) given = load_dataset(o.compare_to, all_views);

  const cli::StopSignals stop;
  ProgressPrinter progress;
  std::printf("capture: %s -> %s (COLMAP on the CPU: features, %s matching, mapping, undistortion)\n",
              o.capture.input.string().c_str(), o.capture.out.string().c_str(), o.capture.matcher.c_str());
  std::fflush(stdout);
  capture::CaptureReport report;
  try {
    report = capture::run_capture(o.capture, [&](const capture::CaptureProgress& p) { progress(p); }, stop.flag());
  } catch (const Error&) {
    progress.finish();
    if (stop.signal()) {
      std::fprintf(stderr, "capture stopped by %s: nothing written\n", cli::stop_signal_name(stop.signal()).c_str());
      cli::set_exit_code(stop.exit_code());
      return;
    }
    throw;
  }
  progress.finish();
  std::printf("%s", capture::report_text(report).c_str());
  if (given) {
    const Dataset captured = load_dataset(report.out, all_views);
    const capture::PoseComparison c = capture::compare_poses(captured, *given, o.compare_to);
    std::printf("%s", capture::comparison_text(c).c_str());
    const fs::path json_path = report.out / "capture_report.json";
    nlohmann::json j = nlohmann::json::parse(capture::report_json(report));
    j["compare_to"] = {{"data_set", fs::absolute(o.compare_to).string()},
                       {"matched", c.matched},
                       {"given", c.given},
                       {"extent", c.extent},
                       {"mean_centre_error_fraction", c.mean_error},
                       {"max_centre_error_fraction", c.max_error},
                       {"mean_direction_error_deg", c.mean_angle_deg},
                       {"scale", c.alignment.scale}};
    const fs::path tmp = json_path.string() + ".tmp";
    std::ofstream(tmp) << j.dump(2) << "\n";
    fs::rename(tmp, json_path);
    std::ofstream(report.out / "capture_report.txt", std::ios::app) << capture::comparison_text(c);
  }
  std::printf("wrote %s (train it with: goris train %s --out RUN)\n", report.out.string().c_str(),
              report.out.string().c_str());
}

void setup_capture(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("capture",
                                "Make a data set from a folder of photos or a video with COLMAP (poses, points, "
                                "undistorted images)");
  c->add_option("input", o->capture.input, "Folder of photos (one camera), or a video file (.mp4, .mov, ...)")->required();
  c->add_option("--out", o->capture.out, "The data set folder to create (it must not exist)")->required();
  c->add_option("--max-images", o->capture.max_images,
                "At most this many photos: evenly spaced, from a video the sharpest of each stretch (default: every "
                "photo of a folder, 100 frames of a video)")
      ->check(cli::whole(0, 100000));
  c->add_option("--resolution", o->capture.width, "Shrink the photos to this width in pixels first (default: keep)")
      ->check(cli::whole(0, 100000));
  c->add_option("--matcher", o->capture.matcher,
                "exhaustive (every pair: best for photos; time grows with the square of their number) or "
                "sequential (each photo with its 10 neighbours: videos, photos taken in order)")
      ->check(CLI::IsMember({"exhaustive", "sequential"}));
  c->add_option("--masks", o->capture.masks,
                "Folder of object masks (MASKS/<photo name>.png, white = object), undistorted with the photos into DATA/masks");
  c->add_option("--camera-model", o->capture.camera_model,
                "COLMAP camera model of the photos (default SIMPLE_RADIAL; OPENCV for strong lens distortion)")
      ->check(CLI::IsMember({"SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL", "OPENCV"}));
  c->add_option("--features", o->capture.max_features, "SIFT features per photo (default 2048; more for hard captures, matching on the CPU takes four times as long for twice as many)")
      ->check(cli::whole(100, 100000));
  c->add_option("--colmap", o->capture.colmap, "The colmap program (default: colmap on PATH)");
  c->add_option("--compare-to", o->compare_to,
                "A data set of the same photos with known poses: align the capture's camera centres to them and "
                "report the distances");
  c->callback([o] { run_capture_command(*o); });
}

}  // namespace

GORIS_COMMAND(12, setup_capture);
