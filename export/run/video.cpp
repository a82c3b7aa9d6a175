#include "export/run/video.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "core/util/error.h"
#include "train/run/run_output_guard.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

// Planar RGB [3][H][W] in [0, 1] (not clamped) into an 8-bit BGR image of size (w, h) at (x0, 0).
void put_frame(cv::Mat& frame, const std::vector<float>& rgb, int w, int h, int x0) {
  const std::size_t hw = std::size_t(w) * std::size_t(h);
  for (int y = 0; y < h; ++y) {
    cv::Vec3b* row = frame.ptr<cv::Vec3b>(y) + x0;
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
      for (int c = 0; c < 3; ++c) {
        const float v = std::clamp(rgb[std::size_t(c) * hw + p], 0.0f, 1.0f);
        row[x][2 - c] = static_cast<unsigned char>(std::lround(v * 255.0f));
      }
    }
  }
}

int even(int v) { return v + (v & 1); }

}  // namespace

VideoProbe probe_video(const fs::path& file) {
  VideoProbe p;
  cv::VideoCapture cap(file.string());
  if (!cap.isOpened()) return p;
  p.width = int(cap.get(cv::CAP_PROP_FRAME_WIDTH));
  p.height = int(cap.get(cv::CAP_PROP_FRAME_HEIGHT));
  p.fps = cap.get(cv::CAP_PROP_FPS);
  // Count by decoding: the container's frame count is an estimate for some codecs.
  cv::Mat m;
  while (cap.read(m)) ++p.frames;
  return p;
}

VideoReport write_video(RunExport& run, const fs::path& out, const VideoSettings& s, RunExport* before,
                        const std::function<void(size_t, size_t)>& on_frame) {
  if (!(s.fps > 0.0 && s.fps <= 240.0)) throw Error(out.string(), "--fps must lie in (0, 240]");
  if (!(s.seconds > 0.0 && s.seconds <= 600.0)) throw Error(out.string(), "--seconds must lie in (0, 600]");
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".mp4") throw Error(out.string(), "a video is written as MPEG-4: the name must end in .mp4");
  check_output_file(out, run_output_guard(run.run_dir(), run.config()));  // never into the data set or the run

  run.require_channel(s.channel);
  if (before) before->require_channel(s.channel);
  const int frames = s.path == RenderPath::Orbit ? std::max(1, int(std::lround(s.seconds * s.fps))) : 0;
  const std::vector<Camera> cams = run.path_cameras(s.path, frames);
  if (cams.empty()) throw Error(out.string(), std::string("the ") + render_path_name(s.path) + " path has no cameras");
  const int w = cams.front().width, h = cams.front().height;
  VideoReport rep;
  rep.file = fs::absolute(out);
  rep.side_by_side = before != nullptr;
  rep.width = even(rep.side_by_side ? 2 * w : w);
  rep.height = even(h);
  rep.fps = s.fps;

  // The temporary name keeps the .mp4 extension: OpenCV picks the container from it.
  std::string tmp_name = rep.file.stem().string();
  tmp_name.insert(0, 1, '.');
  tmp_name += ".partial.mp4";
  const fs::path tmp = rep.file.parent_path() / tmp_name;
  std::error_code ec;
  fs::remove(tmp, ec);
  {
    cv::VideoWriter writer(tmp.string(), cv::VideoWriter::fourcc('m', 'p', '4', 'v'), s.fps,
                           cv::Size(rep.width, rep.height));
    if (!writer.isOpened())
      throw Error(out.string(), "OpenCV cannot open an MPEG-4 video writer here (no ffmpeg backend or encoder)");
    cv::Mat frame(rep.height, rep.width, CV_8UC3, cv::Scalar(0, 0, 0));
    for (std::size_t i = 0; i < cams.size(); ++i) {
      if (cams[i].width != w || cams[i].height != h)
        throw Error(out.string(), "the path's cameras differ in size: a video needs one frame size");
      if (before) {
        put_frame(frame, before->render(cams[i], s.channel), w, h, 0);
        put_frame(frame, run.render(cams[i], s.channel), w, h, w);
      } else {
        put_frame(frame, run.render(cams[i], s.channel), w, h, 0);
      }
      writer.write(frame);
      if (on_frame) on_frame(i + 1, cams.size());
    }
    writer.release();
  }
  const VideoProbe p = probe_video(tmp);
  if (p.frames != int(cams.size()) || p.width != rep.width || p.height != rep.height) {
    fs::remove(tmp, ec);
    throw Error(out.string(), "the encoded video reads back as " + std::to_string(p.frames) + " frames of " +
                                  std::to_string(p.width) + "x" + std::to_string(p.height) + ", expected " +
                                  std::to_string(cams.size()) + " of " + std::to_string(rep.width) + "x" +
                                  std::to_string(rep.height));
  }
  fs::rename(tmp, rep.file, ec);
  if (ec) throw Error(out.string(), "cannot move the finished video into place: " + ec.message());
  rep.frames = p.frames;
  return rep;
}

}  // namespace goris
