#pragma once
// Turntable and before/after videos of a run (`goris export --video`, `goris demo`): the run's renderer
// along a camera path (export/frames/camera_path.h), encoded by OpenCV's video writer as MPEG-4 Part 2
// ('mp4v' in an .mp4 container, which every common player and browser plays through ffmpeg-based stacks).
//
// The orbit path has seconds * fps frames, evenly spaced around the circle (one full turn); the test and
// train paths show every view of that split once, at fps. With a `before` run (the scene with the
// target), each frame is before | after side by side from the same camera. Any rendered channel can be
// shown instead of the final colour (albedo, F0, roughness, normal, depth, G, ...: RunExport::render).
// Frames are 8-bit sRGB as the PNG renders are, padded by one black pixel where a side is odd (the codec
// needs even sizes).
// The file is written under a temporary name, read back (frame count and size must match what was
// written) and only then renamed into place, so a failed or cut-short encode never leaves a half video.
#include <filesystem>
#include <functional>

#include "export/run/run_export.h"

namespace goris {

struct VideoSettings {
  RenderPath path = RenderPath::Orbit;
  double seconds = 10.0;  // orbit: the length of one turn
  double fps = 24.0;
  Channel channel = Channel::Final;  // what each frame shows (render/maps/channels.h), both sides alike
};

struct VideoReport {
  std::filesystem::path file;
  int frames = 0, width = 0, height = 0;  // as encoded (side by side: both halves)
  double fps = 0;
  bool side_by_side = false;
};

// Throws goris::Error naming `out` when the settings are out of range (fps in (0, 240], seconds in (0, 600]),
// the name does not end in .mp4, the writer cannot be opened (no encoder) or the file reads back wrong.
// on_frame(done, total) reports progress.
VideoReport write_video(RunExport& run, const std::filesystem::path& out, const VideoSettings& settings,
                        RunExport* before = nullptr, const std::function<void(size_t, size_t)>& on_frame = {});

// Frame count and size of a video file as OpenCV reads it back (frames = 0 when it cannot be opened).
struct VideoProbe {
  int frames = 0, width = 0, height = 0;
  double fps = 0;
};
VideoProbe probe_video(const std::filesystem::path& file);

}  // namespace goris
