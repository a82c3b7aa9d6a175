#include "core/capture/capture_frames.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris::capture {
namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

// `image` shrunk to `width` pixels wide (never enlarged); the height keeps the aspect.
cv::Mat shrink_to(const cv::Mat& image, int width, int interpolation = cv::INTER_AREA) {
  if (width <= 0 || image.cols <= width) return image;
  const int height = std::max(1, int(std::lround(double(image.rows) * width / image.cols)));
  cv::Mat out;
  cv::resize(image, out, cv::Size(width, height), 0, 0, interpolation);
  return out;
}

void write_png(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) throw Error(path.string(), "cannot write the image");
}

// Each frame's sharpness, read at a small size (a first pass over the video).
std::vector<double> video_scores(const fs::path& video, const std::function<void(int, int)>& on_progress) {
  cv::VideoCapture cap(video.string());
  const int expected = std::max(0, int(cap.get(cv::CAP_PROP_FRAME_COUNT)));
  std::vector<double> scores;
  cv::Mat frame;
  while (cap.read(frame)) {
    if (frame.empty()) break;
    scores.push_back(sharpness(shrink_to(frame, 480)));
    if (on_progress && scores.size() % 10 == 0) on_progress(int(scores.size()), std::max(expected, int(scores.size())));
  }
  if (scores.empty()) throw Error(video.string(), "no frame could be decoded (empty or damaged video)");
  return scores;
}

}  // namespace

bool is_video_file(const fs::path& path) {
  const std::string e = lower_extension(path);
  return e == ".mp4" || e == ".mov" || e == ".avi" || e == ".mkv" || e == ".webm" || e == ".m4v";
}

std::vector<fs::path> list_image_files(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(dir.string(), "folder not found");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file(ec) && loaders::is_image_extension(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

int check_capture_input(const fs::path& input) {
  std::error_code ec;
  if (!fs::exists(input, ec)) throw Error(input.string(), "not found (give a folder of photos or a video file)");
  if (fs::is_directory(input, ec)) return int(list_image_files(input).size());
  if (!is_video_file(input))
    throw Error(input.string(), "not a folder of images or a video file (.mp4, .mov, .avi, .mkv, .webm, .m4v)");
  cv::VideoCapture cap(input.string());
  cv::Mat frame;
  if (!cap.isOpened() || !cap.read(frame) || frame.empty())
    throw Error(input.string(), "cannot read the video (not a video OpenCV's FFmpeg can decode, or damaged)");
  return -1;
}

double sharpness(const cv::Mat& image) {
  cv::Mat grey, lap;
  if (image.channels() == 1) grey = image;
  else cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  cv::Laplacian(grey, lap, CV_64F);
  cv::Scalar mean, dev;
  cv::meanStdDev(lap, mean, dev);
  return dev[0] * dev[0];
}

std::vector<int> pick_sharpest(const std::vector<double>& scores, int count) {
  const int n = int(scores.size());
  std::vector<int> picks;
  if (count <= 0 || count >= n) {
    for (int i = 0; i < n; ++i) picks.push_back(i);
    return picks;
  }
  for (int w = 0; w < count; ++w) {
    const int begin = int(int64_t(w) * n / count), end = int(int64_t(w + 1) * n / count);
    int best = begin;
    for (int i = begin; i < end; ++i)
      if (scores[size_t(i)] > scores[size_t(best)]) best = i;
    picks.push_back(best);
  }
  return picks;
}

PickedFrames write_frames(const fs::path& input, const fs::path& out_dir, const FrameOptions& options,
                          const std::function<void(int, int)>& on_progress) {
  PickedFrames r;
  std::error_code ec;
  auto note_size = [&](const cv::Mat& m) {
    if (r.width == 0) r.width = m.cols, r.height = m.rows;
  };
  if (check_capture_input(input) < 0) {
    r.from_video = true;
    const std::vector<double> scores = video_scores(input, on_progress);
    r.candidates = int(scores.size());
    const std::vector<int> picks = pick_sharpest(scores, options.max_images > 0 ? options.max_images : 100);
    cv::VideoCapture cap(input.string());
    cv::Mat frame;
    size_t next = 0;
    for (int i = 0; next < picks.size() && cap.read(frame); ++i) {
      if (i != picks[next]) continue;
      const cv::Mat out = shrink_to(frame, options.width);
      note_size(out);
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.png", i);
      write_png(out_dir / name, out);
      r.names.push_back(name);
      ++next;
      if (on_progress) on_progress(int(next), int(picks.size()));
    }
    if (r.names.size() != picks.size())
      throw Error(input.string(), "the video ended early on the second read (damaged file)");
    return r;
  }
  const std::vector<fs::path> files = list_image_files(input);
  r.candidates = int(files.size());
  // Evenly spaced when there are more than --max-images (a folder of photos is usually all sharp).
  std::vector<double> order(files.size(), 0.0);
  for (size_t i : pick_sharpest(order, options.max_images)) {
    const cv::Mat image = cv::imread(files[i].string(), cv::IMREAD_COLOR);
    if (image.empty()) throw Error(files[i].string(), "cannot read the image (damaged, or not an image)");
    const cv::Mat out = shrink_to(image, options.width);
    if (r.width != 0 && (out.cols != r.width || out.rows != r.height))
      throw Error(files[i].string(), "is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                                         " while the images before it are another size: a capture needs one camera");
    note_size(out);
    const std::string name = files[i].stem().string() + ".png";
    write_png(out_dir / name, out);
    r.names.push_back(name);
    if (on_progress) on_progress(int(r.names.size()), std::min(int(files.size()), options.max_images > 0 ? options.max_images : int(files.size())));
  }
  return r;
}

void write_masks(const fs::path& masks_dir, const fs::path& input_dir, const std::vector<std::string>& names,
                 const fs::path& out_dir, int width, int height) {
  std::map<std::string, fs::path> by_stem;
  for (const fs::path& p : list_image_files(masks_dir)) by_stem.emplace(p.stem().string(), p);
  for (const std::string& name : names) {
    const std::string stem = fs::path(name).stem().string();
    auto it = by_stem.find(stem);
    if (it == by_stem.end())
      throw Error(masks_dir.string(), "no mask for image '" + stem + "' (expected " + (masks_dir / stem).string() + ".png)");
    cv::Mat mask = cv::imread(it->second.string(), cv::IMREAD_GRAYSCALE);
    if (mask.empty()) throw Error(it->second.string(), "cannot read the mask");
    if (mask.cols != width || mask.rows != height) {
      if (std::abs(double(mask.cols) / mask.rows - double(width) / height) > 0.01)
        throw Error(it->second.string(), "is " + std::to_string(mask.cols) + "x" + std::to_string(mask.rows) +
                                             ", another shape than its image " + (input_dir / name).string());
      cv::resize(mask, mask, cv::Size(width, height), 0, 0, cv::INTER_AREA);
    }
    write_png(out_dir / name, mask);
  }
}

}  // namespace goris::capture
