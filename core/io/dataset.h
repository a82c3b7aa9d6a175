#pragma once
// Data sets: a list of posed views (camera + image file + optional masks) split into train and test, plus
// SfM points when the format has them. Every loader converts its cameras to the one convention of
// core/io/camera.h (world-to-camera, OpenCV axes) and applies the requested downscale to the intrinsics;
// load_view_image / load_view_mask apply the same downscale to the pixels, so images, masks and cameras
// always agree.
//
// Formats (detected by load_dataset from the files present):
//   nerf-synthetic  transforms_train.json + transforms_test.json (+ transforms_val.json, unused)
//   instant-ngp     transforms.json (fl_x/fl_y/cx/cy, k1/k2/k3/p1/p2, w/h, per-frame overrides)
//   colmap-binary   sparse/0/{cameras,images,points3D}.bin (or sparse/), images/ beside sparse/
//   colmap-text     the same with .txt files
//   llff            poses_bounds.npy + images/
// Masks are matched by name: mask_XXX.png / gloss_XXX.png beside r_XXX.png (GOR-IS layout, which also
// puts full_XXX.png beside test views), or masks/<image stem>.* and gloss/<image stem>.* in the data set
// folder.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/compute/device.h"
#include "core/io/camera.h"
#include "core/io/image.h"

namespace goris {

struct View {
  std::string name;                   // image file stem, e.g. "r_000"
  Camera camera;                      // at the loaded resolution (after downscale)
  std::filesystem::path image;        // the photo / render
  int source_width = 0, source_height = 0;  // size of the image file on disk
  std::optional<std::filesystem::path> object_mask;  // target object (white = object)
  std::optional<std::filesystem::path> glossy_mask;  // glossy surfaces (the paper's M_gt)
  std::optional<std::filesystem::path> full_image;   // GOR-IS test views: the same view WITH the target
  // With DatasetOptions::undistort: the lens distortion the images are undistorted by when they are loaded
  // (camera is then the pinhole camera of the undistorted images); zero otherwise.
  Distortion lens;
};

struct SfmPoints {
  std::vector<glm::vec3> xyz;
  std::vector<glm::vec3> rgb;  // [0, 1]
  size_t size() const { return xyz.size(); }
};

// Sphere around the camera centres (the 3DGS "cameras extent"): centre = their mean,
// radius = 1.1 x the largest distance from it.
struct SceneBounds {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

struct DatasetOptions {
  glm::vec3 background{0.0f};  // RGBA images are composited on this colour
  float downscale = 1.0f;      // divide the image size by this (>= 1 shrinks)
  int target_width = 0;        // --resolution: width in pixels (height keeps the aspect); overrides downscale
  // Formats without their own split (instant-ngp, COLMAP, LLFF) hold out every N-th view (index % N == 0,
  // in file-name order for COLMAP and LLFF, frame order for instant-ngp) as the test split; 0 = no test views.
  int test_every = 8;
  // Undistort the photos and masks of cameras with lens distortion as they are loaded, onto the same pinhole
  // intrinsics (View::lens keeps what was removed): the renderers model pinhole cameras only. Off, the
  // cameras keep their distortion as the files give it (`goris info`, the loaders' tests).
  bool undistort = false;
};

struct Dataset {
  std::string format;  // "nerf-synthetic", "instant-ngp", "colmap-binary", "colmap-text", "llff"
  std::filesystem::path root;         // the data set folder
  std::filesystem::path source;       // the file the cameras came from (transforms json, sparse folder...)
  std::vector<View> train, test;
  SfmPoints points;                   // empty when the format has none
  std::optional<glm::vec2> depth_range;  // LLFF near/far over all views (before any rescaling)
  std::vector<std::string> warnings;  // non-fatal problems (e.g. frames skipped), for the caller to show

  size_t view_count() const { return train.size() + test.size(); }
  SceneBounds camera_bounds() const;
};

// Detects the format of `path` (a data set folder, or one of its camera files) and loads it. Throws
// goris::Error naming the file and the problem for every bad input, including a data set with no images.
Dataset load_dataset(const std::filesystem::path& path, const DatasetOptions& options = {});

// Name of the detected format, without loading ("nerf-synthetic", ...); throws when nothing is recognised.
std::string detect_dataset_format(const std::filesystem::path& path);

// The view's image as RGB on `device` at view.camera's size, RGBA composited on options.background.
// alpha: when given, the image's alpha channel at the camera's size (CPU), or nothing when it has none.
Image load_view_image(const View& view, const DatasetOptions& options, Device device = Device::CPU,
                      std::optional<Image>* alpha = nullptr);
// The view's object / glossy mask as one channel in [0, 1] at view.camera's size; throws when the view
// has no such mask.
Image load_view_object_mask(const View& view, Device device = Device::CPU);
Image load_view_glossy_mask(const View& view, Device device = Device::CPU);
// GOR-IS test views: the render with the target, at view.camera's size.
Image load_view_full_image(const View& view, const DatasetOptions& options, Device device = Device::CPU);

// `image` (HWC, any channels, on the CPU) undistorted by `lens` onto `pinhole` (its size and intrinsics):
// what the loaders do to every image and mask of a view with View::lens set.
Image undistort_image(const Image& image, const Camera& pinhole, const Distortion& lens);

// The size images of (width, height) are loaded at under `options` (at least 1x1).
ImageSize scaled_size(int width, int height, const DatasetOptions& options);

SceneBounds camera_bounds(const std::vector<View>& views);
// The views' cameras, in order.
std::vector<Camera> cameras_of(const std::vector<View>& views);

}  // namespace goris
