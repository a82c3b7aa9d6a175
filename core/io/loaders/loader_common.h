#pragma once
// Internal pieces shared by the data set loaders (not part of the public API).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/dataset.h"
#include "core/io/loaders/transforms_json.h"

namespace goris::loaders {

// The loaders, one per format (format_detect.cpp picks one).
Dataset load_nerf_synthetic(const std::filesystem::path& root, const DatasetOptions& options);
Dataset load_instant_ngp(const std::filesystem::path& json_path, const DatasetOptions& options);
Dataset load_colmap(const std::filesystem::path& root, const std::filesystem::path& sparse_dir,
                    const DatasetOptions& options);
Dataset load_llff(const std::filesystem::path& root, const DatasetOptions& options);

// A camera at the image file's size from transforms*.json intrinsics (declared w/h, when given, are fitted
// to the file's size) and a camera-to-world matrix in OpenGL/Blender axes (x right, y up, z back).
Camera camera_from_transforms(const TransformsIntrinsics& intr, const glm::dmat4& c2w_gl, ImageSize file_size,
                              const std::filesystem::path& image, const std::string& json, const std::string& what);

// World-to-camera pose (OpenCV axes) from a camera-to-world rotation whose columns are the camera's
// x (right), y (down), z (forward) axes in world coordinates, and the camera centre. The rotation is
// checked to be orthonormal with det +1 (else a goris::Error naming `file` and `what`) and
// re-orthonormalised.
void set_pose_from_c2w(Camera& cam, const glm::dmat3& c2w_rotation, const glm::dvec3& center,
                       const std::string& file, const std::string& what);
// The same from COLMAP's world-to-camera quaternion (w, x, y, z) and translation.
void set_pose_from_qt(Camera& cam, const double q[4], const double t[3]);

// Throws goris::Error(file, what + ...) when any intrinsic or pose value of `c` is not a finite float
// (e.g. a translation of 1e60 in a double-precision file).
void require_finite_camera(const Camera& c, const std::string& file, const std::string& what);

// A camera declared for an image of declared.width x declared.height used with an image file of `actual` size:
// the same camera when they agree, intrinsics scaled when the file is a resized copy with the same aspect
// ratio (within 1%), otherwise an error naming both files.
Camera fit_camera_to_image(const Camera& declared, ImageSize actual, const std::filesystem::path& image,
                           const std::string& camera_source);

// Finds the masks of a view by name (see core/io/dataset.h) and checks that their size matches the image.
// Folder listings are cached, so one finder should serve a whole data set.
class MaskFinder {
 public:
  explicit MaskFinder(std::filesystem::path dataset_root) : root_(std::move(dataset_root)) {}
  // Sets v.object_mask / glossy_mask / full_image from the files found; v.image and v.source_* must be set.
  void attach(View& v);

 private:
  // Image files of `dir` by stem; empty when the folder does not exist.
  const std::map<std::string, std::filesystem::path>& listing(const std::filesystem::path& dir);
  std::optional<std::filesystem::path> find(const std::filesystem::path& dir, const std::string& stem);
  std::filesystem::path root_;
  std::map<std::filesystem::path, std::map<std::string, std::filesystem::path>> cache_;
};

// Finishes a view whose camera is at the image file's size: attaches its masks and applies the options'
// downscale to the camera. The view's name is the image's stem.
View make_view(const Camera& camera_at_file_size, const std::filesystem::path& image, MaskFinder& masks,
               const DatasetOptions& options);

// Splits views into train / test: every options.test_every-th view (index % N == 0) is a test view.
void split_every_nth(std::vector<View> views, const DatasetOptions& options, Dataset& out);

// Throws the "no images" error for `source` when the data set has no views at all.
void require_views(const Dataset& d, const std::string& source);

// Finds an existing image file for `base` (which may lack its extension): base itself, then base + .png,
// .jpg, .jpeg, .PNG, .JPG, .JPEG. Returns an empty path when none exists.
std::filesystem::path find_image_file(const std::filesystem::path& base);

bool is_image_extension(const std::filesystem::path& p);

}  // namespace goris::loaders
