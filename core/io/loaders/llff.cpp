// LLFF folders: poses_bounds.npy, images/ (in file-name order, one per pose row), optional masks/.
#include <algorithm>
#include <cmath>
#include <system_error>

#include "core/io/loaders/llff_poses.h"
#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris {
namespace fs = std::filesystem;

std::vector<LlffPose> llff_poses_from_npy(const NpyArray& a, const std::string& name) {
  if (a.shape.size() != 2 || a.shape[1] != 17) {
    std::string s = "(";
    for (size_t i = 0; i < a.shape.size(); ++i) s += (i ? ", " : "") + std::to_string(a.shape[i]);
    throw Error(name, "expected an N x 17 array of poses and bounds, got shape " + s + ")");
  }
  if (a.shape[0] == 0) throw Error(name, "no poses (0 rows)");
  std::vector<LlffPose> poses(a.shape[0]);
  for (size_t i = 0; i < poses.size(); ++i) {
    for (size_t j = 0; j < 17; ++j)
      if (!std::isfinite(a.at(i, j))) throw Error(name, "row " + std::to_string(i) + " has a non-finite value");
    LlffPose& p = poses[i];
    auto m = [&](int r, int c) { return a.at(i, size_t(r * 5 + c)); };
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) p.c2w_llff[c][r] = m(r, c);
    p.center = glm::dvec3(m(0, 3), m(1, 3), m(2, 3));
    p.height = m(0, 4);
    p.width = m(1, 4);
    p.focal = m(2, 4);
    p.near = a.at(i, 15);
    p.far = a.at(i, 16);
    if (!(p.height > 0 && p.width > 0 && p.focal > 0))
      throw Error(name, "row " + std::to_string(i) + ": image height, width and focal length must be positive");
  }
  return poses;
}

namespace loaders {

Dataset load_llff(const fs::path& root, const DatasetOptions& options) {
  const fs::path npy = root / "poses_bounds.npy";
  const std::vector<LlffPose> poses = llff_poses_from_npy(load_npy(npy), npy.string());
  const fs::path image_dir = root / "images";
  std::error_code ec;
  if (!fs::is_directory(image_dir, ec)) throw Error(image_dir.string(), "images folder not found (LLFF expects images/ beside poses_bounds.npy)");
  std::vector<fs::path> images;
  for (const auto& e : fs::directory_iterator(image_dir, ec))
    if (e.is_regular_file(ec) && is_image_extension(e.path())) images.push_back(e.path());
  std::sort(images.begin(), images.end());
  if (images.empty()) throw Error(image_dir.string(), "no images: the folder has no image files");
  if (images.size() != poses.size())
    throw Error(npy.string(), "has " + std::to_string(poses.size()) + " poses but " + image_dir.string() + " has " +
                                  std::to_string(images.size()) + " images");

  Dataset d;
  d.format = "llff";
  d.root = root;
  d.source = npy;
  MaskFinder masks(root);
  std::vector<View> views;
  views.reserve(poses.size());
  glm::vec2 range(INFINITY, -INFINITY);
  for (size_t i = 0; i < poses.size(); ++i) {
    const LlffPose& p = poses[i];
    const ImageSize s = probe_image_size(images[i]);
    // hwf describes the original photos; the files may be downscaled copies (goldcape: 3648 -> 456).
    const double scale = s.width / p.width;
    if (std::abs(s.height / (p.height * scale) - 1.0) > 0.01)
      throw Error(images[i].string(), "image is " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                                          " but row " + std::to_string(i) + " of " + npy.string() + " declares " +
                                          std::to_string(int(p.width)) + "x" + std::to_string(int(p.height)) +
                                          " (a different aspect ratio)");
    Camera cam;
    cam.width = s.width;
    cam.height = s.height;
    cam.fx = cam.fy = float(p.focal * scale);
    cam.cx = 0.5f * s.width;
    cam.cy = 0.5f * s.height;
    // LLFF columns (down, right, back) -> OpenCV (right, down, forward).
    const glm::dmat3 r_cv(p.c2w_llff[1], p.c2w_llff[0], -p.c2w_llff[2]);
    set_pose_from_c2w(cam, r_cv, p.center, npy.string(), "row " + std::to_string(i));
    require_finite_camera(cam, npy.string(), "row " + std::to_string(i));
    views.push_back(make_view(cam, images[i], masks, options));
    range = glm::vec2(std::min(range.x, float(p.near)), std::max(range.y, float(p.far)));
  }
  d.depth_range = range;
  split_every_nth(std::move(views), options, d);
  require_views(d, npy.string());
  return d;
}

}  // namespace loaders
}  // namespace goris
