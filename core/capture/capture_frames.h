#pragma once
// The photos a capture starts from: a folder of images (kept under their own names, so that masks and
// given poses match by name) or a video file (frames picked by OpenCV: the sequence cut into evenly spaced
// windows, the sharpest frame of each window kept, sharpness = variance of the Laplacian). Either way at
// most `max_images` are written, shrunk to `width` pixels wide when given, into a folder for COLMAP.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace goris::capture {

// Whether `path` names a video file by its extension (.mp4, .mov, .avi, .mkv, .webm, .m4v).
bool is_video_file(const std::filesystem::path& path);

// The image files of a folder (by extension), sorted by name. Throws goris::Error naming the folder when it
// is missing.
std::vector<std::filesystem::path> list_image_files(const std::filesystem::path& dir);

// Sharpness of an image: variance of the Laplacian of its grey levels (higher = sharper).
double sharpness(const cv::Mat& image);

// Indices of `count` picks out of `scores` (one per frame): evenly spaced windows, the best score of each.
// All indices when count <= 0 or count >= scores.size(). Sorted.
std::vector<int> pick_sharpest(const std::vector<double>& scores, int count);

// A quick look at `input` before any work: a folder's number of images, or for a video file -1 once its
// first frame decodes. Throws goris::Error naming the file: not found, neither a folder nor a video, a
// video that does not open or decode.
int check_capture_input(const std::filesystem::path& input);

struct FrameOptions {
  int max_images = 0;  // 0: every image of a folder, 100 frames of a video
  int width = 0;       // 0: the input's size
};

struct PickedFrames {
  std::vector<std::string> names;  // file names written into the output folder
  int candidates = 0;              // images in the folder / frames in the video
  int width = 0, height = 0;       // size of the written images
  bool from_video = false;
};

// Writes the picked frames of `input` into `out_dir` (which must exist). on_progress(done, total) follows
// the work. Throws goris::Error naming the file: unreadable video or image, a folder without images.
PickedFrames write_frames(const std::filesystem::path& input, const std::filesystem::path& out_dir,
                          const FrameOptions& options, const std::function<void(int, int)>& on_progress = {});

// The masks of the picked images (masks_dir/<image stem>.*, at the same size as the written images) as
// out_dir/<image name>, the names COLMAP's undistorter looks up. Throws goris::Error naming the image
// whose mask is missing.
void write_masks(const std::filesystem::path& masks_dir, const std::filesystem::path& input_dir,
                 const std::vector<std::string>& names, const std::filesystem::path& out_dir, int width, int height);

}  // namespace goris::capture
