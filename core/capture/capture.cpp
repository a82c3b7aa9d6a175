#include "core/capture/capture.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/capture/capture_frames.h"
#include "core/capture/colmap_progress.h"
#include "core/io/dataset.h"
#include "core/io/loaders/colmap_model.h"
#include "core/io/output_path.h"
#include "core/util/error.h"
#include "core/util/logged_process.h"

namespace goris::capture {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr const char* kTmpMarker = ".goris-capture-tmp";
constexpr int kMinImages = 3;

[[noreturn]] void throw_too_few(const fs::path& input, int images, bool video) {
  throw Error(input.string(), "only " + std::to_string(images) + (video ? " frame" : " photo") + (images == 1 ? "" : "s") +
                                  ": a capture needs at least " + std::to_string(kMinImages) +
                                  " (20 or more, each overlapping its neighbours, work best)");
}

// The temporary folder beside `out`, made through the output guard. One left by a stopped capture (it
// holds the marker file) is removed first; any other folder of that name is refused.
fs::path make_tmp_dir(const fs::path& out) {
  std::string name = ".";  // appended, not "." + ...: GCC 12 warns falsely (-Wrestrict) about the latter
  name += out.filename().string();
  name += ".capture-tmp";
  const fs::path tmp = out.parent_path() / name;
  std::error_code ec;
  if (fs::exists(tmp, ec)) {
    if (!fs::exists(tmp / kTmpMarker, ec))
      throw Error(tmp.string(), "exists and is not a capture's temporary folder: move it away first");
    fs::remove_all(tmp, ec);
  }
  check_output_dir(tmp);
  std::ofstream(tmp / kTmpMarker) << "temporary folder of a `goris capture` run; safe to delete\n";
  return tmp;
}

// Cleans up the temporary folder unless the capture finished (then it has been renamed away): after a
// COLMAP stage failed its logs stay (the error names them; the next capture to the same --out removes
// them), everything else goes.
struct TmpRemover {
  fs::path dir;
  const std::atomic<bool>* stop = nullptr;
  ~TmpRemover() {
    if (dir.empty()) return;
    std::error_code ec;
    const bool stopped = stop && stop->load();
    if (stopped || fs::is_empty(dir / "capture_logs", ec) || ec) fs::remove_all(dir, ec);
    else fs::remove_all(dir / "work", ec);
  }
};

class StageRunner {
 public:
  StageRunner(fs::path colmap, fs::path logs, int stage_count, const std::function<void(const CaptureProgress&)>& on_progress,
              const std::atomic<bool>* stop, CaptureReport& report)
      : colmap_(std::move(colmap)), logs_(std::move(logs)), count_(stage_count), on_progress_(on_progress), stop_(stop),
        report_(report) {}

  void report(const std::string& stage, int index, Clock::time_point start, int done, int total) {
    if (!on_progress_) return;
    CaptureProgress p{stage, index, count_, done, total, seconds_since(start), -1};
    if (done > 0 && total > done) p.eta_s = p.stage_seconds / done * (total - done);
    if (done >= total && total > 0) p.eta_s = 0;
    on_progress_(p);
  }

  void check_stop() const {
    if (stop_ && stop_->load()) throw Error(report_.out.string(), "capture stopped before the end: nothing was written");
  }

  // Runs `colmap command args...` as stage `index`; returns its output lines (the last ones) on success,
  // throws goris::Error with the log's tail when it fails.
  // may_fail: a failed run returns false instead of throwing (the mapper fails when it places no photos).
  bool run(const std::string& stage, int index, const std::string& command, std::vector<std::string> args, int images,
           std::vector<std::string>* lines = nullptr, bool may_fail = false) {
    check_stop();
    const auto start = Clock::now();
    const fs::path log = logs_ / (std::to_string(index) + "_" + command + ".log");
    args.insert(args.begin(), command);
    report(stage, index, start, 0, 0);
    ProcessResult r = run_logged(
        colmap_, args, log,
        [&](const std::string& line) {
          if (lines) lines->push_back(line);
          if (auto c = parse_colmap_progress(line, images)) report(stage, index, start, c->done, c->total);
        },
        [this] { return stop_ && stop_->load(); });
    check_stop();
    report_.stages.push_back({stage, seconds_since(start)});
    if (r.exit_code != 0 && may_fail) return false;
    if (r.exit_code != 0) {
      std::string tail;
      for (size_t i = r.last_lines.size() > 8 ? r.last_lines.size() - 8 : 0; i < r.last_lines.size(); ++i)
        tail += "\n  " + r.last_lines[i];
      throw Error(log.string(), "colmap " + command + " failed (exit code " + std::to_string(r.exit_code) + "):" + tail);
    }
    return true;
  }

 private:
  fs::path colmap_, logs_;
  int count_;
  const std::function<void(const CaptureProgress&)>& on_progress_;
  const std::atomic<bool>* stop_;
  CaptureReport& report_;
};

// The mapper's model with the most registered images (COLMAP writes sparse/0, sparse/1... when the photos
// fall apart into several groups), or an empty path when it wrote none.
fs::path largest_model(const fs::path& sparse, int* registered) {
  fs::path best;
  *registered = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(sparse, ec)) {
    if (!e.is_directory(ec)) continue;
    try {
      const int n = int(read_colmap_model(e.path()).images.size());
      if (n > *registered) *registered = n, best = e.path();
    } catch (const Error&) {
    }
  }
  return best;
}

// Whether `path` is `dir` or lies below it (both absolute and normal).
bool is_inside(const fs::path& path, fs::path dir) {
  if (dir.filename().empty()) dir = dir.parent_path();
  auto p = path.begin();
  for (auto d = dir.begin(); d != dir.end(); ++d, ++p)
    if (p == path.end() || *p != *d) return false;
  return true;
}

void move_into(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw Error(to.string(), "cannot move " + from.string() + " here: " + ec.message());
}

}  // namespace

fs::path find_colmap(const fs::path& requested) {
  const std::string install = "install it with `sudo apt-get install colmap` (or ./dev setup)";
  if (!requested.empty()) {
    if (!fs::is_regular_file(requested) || ::access(requested.c_str(), X_OK) != 0)
      throw Error(requested.string(), "no COLMAP executable here; " + install);
    return requested;
  }
  if (auto found = find_on_path("colmap")) return *found;
  throw Error("colmap", "COLMAP not found on PATH; " + install);
}

CaptureReport run_capture(const CaptureOptions& o, const std::function<void(const CaptureProgress&)>& on_progress,
                          const std::atomic<bool>* stop) {
  const auto start = Clock::now();
  CaptureReport rep;
  rep.input = o.input;
  rep.out = fs::absolute(o.out).lexically_normal();
  if (rep.out.filename().empty()) rep.out = rep.out.parent_path();
  rep.matcher = o.matcher;
  rep.camera_model = o.camera_model;
  rep.masks = !o.masks.empty();
  if (o.matcher != "exhaustive" && o.matcher != "sequential")
    throw Error("--matcher", "'" + o.matcher + "' is not a matcher: exhaustive or sequential");
  std::error_code ec;
  const int photos = check_capture_input(o.input);
  const bool video = photos < 0;
  if (!video && photos < kMinImages) throw_too_few(o.input, photos, false);
  if (rep.masks && !fs::is_directory(o.masks, ec)) throw Error(o.masks.string(), "masks folder not found");
  if (fs::exists(rep.out, ec))
    throw Error(rep.out.string(), "exists already: a capture writes a new data set folder (choose another --out)");
  // A data set inside the photo folder would mix with the photos of the next capture of that folder.
  if (!video && is_inside(rep.out, fs::absolute(o.input).lexically_normal()))
    throw Error(rep.out.string(), "lies inside the input folder " + o.input.string() +
                                      ": choose an output folder outside it (e.g. beside it)");
  const fs::path colmap = find_colmap(o.colmap);
  if (video && rep.masks) throw Error(o.masks.string(), "--masks needs a folder of photos, not a video");

  const fs::path tmp = make_tmp_dir(rep.out);
  TmpRemover remover{tmp, stop};
  const fs::path work = tmp / "work", input = work / "input", logs = tmp / "capture_logs";
  for (const fs::path& d : {work, input, logs, work / "sparse"}) fs::create_directories(d);

  const int stage_count = 5;
  StageRunner stages(colmap, logs, stage_count, on_progress, stop, rep);

  // 1. The photos.
  const auto frames_start = Clock::now();
  const PickedFrames picked = write_frames(o.input, input, {o.max_images, o.width}, [&](int done, int total) {
    stages.check_stop();
    stages.report("frames", 1, frames_start, done, total);
  });
  rep.from_video = picked.from_video;
  rep.candidates = picked.candidates;
  rep.images = int(picked.names.size());
  rep.width = picked.width, rep.height = picked.height;
  if (rep.images < kMinImages) throw_too_few(o.input, rep.images, video);
  if (rep.masks) {
    fs::create_directories(work / "masks_input");
    write_masks(o.masks, input, picked.names, work / "masks_input", picked.width, picked.height);
  }
  rep.stages.push_back({"frames", seconds_since(frames_start)});

  // 2.-5. COLMAP.
  const std::string db = (work / "database.db").string();
  // SIFT's doubled first octave finds features in small photos; on photos of 480 px and more it costs four
  // times the CPU time for few extra matches.
  const bool small = std::max(rep.width, rep.height) < 480;
  const std::string first_octave = small ? "-1" : "0";
  stages.run("features", 2, "feature_extractor",
             {"--database_path", db, "--image_path", input.string(), "--ImageReader.single_camera", "1",
              "--ImageReader.camera_model", o.camera_model, "--SiftExtraction.use_gpu", "0",
              "--SiftExtraction.max_num_features", std::to_string(o.max_features), "--SiftExtraction.first_octave",
              first_octave},
             rep.images);
  if (o.matcher == "exhaustive")
    stages.run("matching", 3, "exhaustive_matcher",
               {"--database_path", db, "--SiftMatching.use_gpu", "0", "--ExhaustiveMatching.block_size", "10"}, rep.images);
  else
    stages.run("matching", 3, "sequential_matcher",
               {"--database_path", db, "--SiftMatching.use_gpu", "0", "--SequentialMatching.overlap", "10"}, rep.images);
  // Small photos have few features: the mapper's inlier thresholds are lowered to match.
  std::vector<std::string> mapper{"--database_path", db, "--image_path", input.string(), "--output_path",
                                  (work / "sparse").string()};
  if (small) mapper.insert(mapper.end(), {"--Mapper.init_min_num_inliers", "30", "--Mapper.abs_pose_min_num_inliers", "15"});
  stages.run("mapping", 4, "mapper", mapper, rep.images, nullptr, true);
  const fs::path model = largest_model(work / "sparse", &rep.registered);
  if (rep.registered < kMinImages)
    throw Error(o.input.string(),
                "mapping failed: COLMAP registered " + std::to_string(rep.registered) + " of " + std::to_string(rep.images) +
                    " photos. Try photos with more overlap (each seen from a few degrees further than the last), " +
                    (o.matcher == "sequential" ? "--matcher exhaustive, " : "") + "more photos (--max-images), or " +
                    "a larger --resolution; COLMAP's logs are in " + logs.string());

  // Statistics of the model (points, reprojection error).
  std::vector<std::string> analysis;
  stages.run("analysis", 4, "model_analyzer", {"--path", model.string()}, rep.images, &analysis);
  rep.stages.pop_back();  // a fraction of a second: counted with the mapping
  for (const std::string& line : analysis) {
    const size_t at = line.find("Mean reprojection error:");
    if (at != std::string::npos) std::sscanf(line.c_str() + at, "Mean reprojection error: %lf", &rep.mean_reprojection_error_px);
    const size_t pts = line.find("Points:");
    if (pts != std::string::npos) std::sscanf(line.c_str() + pts, "Points: %lld", &rep.points);
  }

  stages.run("undistorting", 5, "image_undistorter",
             {"--image_path", input.string(), "--input_path", model.string(), "--output_path", (work / "dense").string(),
              "--output_type", "COLMAP"},
             rep.registered);
  if (rep.masks) {
    stages.run("undistorting", 5, "image_undistorter",
               {"--image_path", (work / "masks_input").string(), "--input_path", model.string(), "--output_path",
                (work / "dense_masks").string(), "--output_type", "COLMAP"},
               rep.registered);
    rep.stages.back().seconds += rep.stages[rep.stages.size() - 2].seconds;
    rep.stages.erase(rep.stages.end() - 2);
  }

  // The data set: images/, sparse/0, masks/.
  move_into(work / "dense" / "images", tmp / "images");
  fs::create_directories(tmp / "sparse");
  move_into(work / "dense" / "sparse", tmp / "sparse" / "0");
  if (rep.masks) move_into(work / "dense_masks" / "images", tmp / "masks");
  fs::remove_all(work, ec);
  fs::remove(tmp / kTmpMarker, ec);
  load_dataset(tmp);  // what `goris train` will read: a problem shows now, not later
  rep.seconds_total = seconds_since(start);
  auto write = [&](const fs::path& p, const std::string& text) {
    std::ofstream f(p);
    f << text;
    if (!f) throw Error(p.string(), "cannot write the report");
  };
  write(tmp / "capture_report.json", report_json(rep));
  write(tmp / "capture_report.txt", report_text(rep));
  stages.check_stop();
  fs::rename(tmp, rep.out, ec);
  if (ec) throw Error(rep.out.string(), "cannot rename the finished capture " + tmp.string() + " into place: " + ec.message());
  remover.dir.clear();
  return rep;
}

std::string report_json(const CaptureReport& r) {
  nlohmann::json j;
  j["input"] = r.input.string();
  j["out"] = r.out.string();
  j["from_video"] = r.from_video;
  j["candidates"] = r.candidates;
  j["images"] = r.images;
  j["registered"] = r.registered;
  j["registered_fraction"] = r.images ? double(r.registered) / r.images : 0.0;
  j["width"] = r.width;
  j["height"] = r.height;
  j["points"] = r.points;
  j["mean_reprojection_error_px"] = r.mean_reprojection_error_px;
  j["matcher"] = r.matcher;
  j["camera_model"] = r.camera_model;
  j["masks"] = r.masks;
  nlohmann::json stages = nlohmann::json::object();
  for (const StageTime& s : r.stages) stages[s.stage] = s.seconds;
  j["seconds"] = stages;
  j["seconds_total"] = r.seconds_total;
  return j.dump(2) + "\n";
}

std::string report_text(const CaptureReport& r) {
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "capture of %s -> %s\n", r.input.string().c_str(), r.out.string().c_str());
  s += buf;
  std::snprintf(buf, sizeof buf, "photos: %d given to COLMAP (%dx%d, of %d %s), %d registered (%.1f %%)\n", r.images,
                r.width, r.height, r.candidates, r.from_video ? "video frames" : "in the folder", r.registered,
                r.images ? 100.0 * r.registered / r.images : 0.0);
  s += buf;
  std::snprintf(buf, sizeof buf, "model: %lld 3D points, mean reprojection error %.3f px (%s cameras, %s matching)%s\n",
                r.points, r.mean_reprojection_error_px, r.camera_model.c_str(), r.matcher.c_str(),
                r.masks ? ", masks undistorted with the photos" : "");
  s += buf;
  s += "time:";
  for (const StageTime& t : r.stages) {
    std::snprintf(buf, sizeof buf, " %s %.1f s,", t.stage.c_str(), t.seconds);
    s += buf;
  }
  std::snprintf(buf, sizeof buf, " total %.1f s\n", r.seconds_total);
  s += buf;
  if (r.registered < r.images * 0.9)
    s += "warning: " + std::to_string(r.images - r.registered) + " photos were not placed and are left out: try " +
         (r.matcher == "sequential" ? std::string("--matcher exhaustive, ") : std::string()) +
         "a larger --resolution or more --features, or photos with more overlap\n";
  return s;
}

}  // namespace goris::capture
