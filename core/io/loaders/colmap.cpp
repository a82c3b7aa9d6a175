// COLMAP folders: sparse/0 (or sparse/) with cameras, images and points3D in binary or text, and the photos
// in images/ beside sparse/.
#include <algorithm>
#include <system_error>
#include <unordered_map>
#include <unordered_set>

#include "core/io/file_bytes.h"
#include "core/io/loaders/colmap_model.h"
#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris {
namespace fs = std::filesystem;

ColmapSparseModel read_colmap_model(const fs::path& sparse, bool* binary_out) {
  std::error_code ec;
  if (!fs::is_directory(sparse, ec)) throw Error(sparse.string(), "COLMAP sparse folder not found");
  const bool binary = fs::exists(sparse / "cameras.bin", ec);
  if (!binary && !fs::exists(sparse / "cameras.txt", ec))
    throw Error(sparse.string(), "no COLMAP model: neither cameras.bin nor cameras.txt");
  const char* ext = binary ? ".bin" : ".txt";
  const fs::path cameras = sparse / (std::string("cameras") + ext), images = sparse / (std::string("images") + ext),
                 points = sparse / (std::string("points3D") + ext);
  if (!fs::exists(images, ec)) throw Error(images.string(), "file not found (the COLMAP model in " + sparse.string() + " is incomplete)");
  ColmapSparseModel m;
  if (binary) {
    auto b = read_file_bytes(cameras);
    m.cameras = parse_colmap_cameras_bin(b.data(), b.size(), cameras.string());
    b = read_file_bytes(images);
    m.images = parse_colmap_images_bin(b.data(), b.size(), images.string());
    if (fs::exists(points, ec)) {
      b = read_file_bytes(points);
      m.points = parse_colmap_points3d_bin(b.data(), b.size(), points.string());
    }
  } else {
    m.cameras = parse_colmap_cameras_txt(read_text_file(cameras), cameras.string());
    m.images = parse_colmap_images_txt(read_text_file(images), images.string());
    if (fs::exists(points, ec)) m.points = parse_colmap_points3d_txt(read_text_file(points), points.string());
  }
  std::unordered_set<uint32_t> camera_ids;
  for (const auto& c : m.cameras) camera_ids.insert(c.id);
  for (const auto& im : m.images) {
    if (!camera_ids.count(im.camera_id))
      throw Error(images.string(), "image " + std::to_string(im.id) + " ('" + im.name + "') refers to camera " +
                                       std::to_string(im.camera_id) + ", which " + cameras.string() + " does not define");
  }
  if (binary_out) *binary_out = binary;
  return m;
}

namespace loaders {
namespace {

Camera intrinsics_from_colmap(const ColmapCamera& c) {
  Camera cam;
  cam.width = int(c.width);
  cam.height = int(c.height);
  const auto& p = c.params;
  switch (c.model) {
    case ColmapModel::SimplePinhole: cam.fx = cam.fy = float(p[0]), cam.cx = float(p[1]), cam.cy = float(p[2]); break;
    case ColmapModel::Pinhole: cam.fx = float(p[0]), cam.fy = float(p[1]), cam.cx = float(p[2]), cam.cy = float(p[3]); break;
    case ColmapModel::SimpleRadial:
      cam.fx = cam.fy = float(p[0]), cam.cx = float(p[1]), cam.cy = float(p[2]);
      cam.dist.k1 = float(p[3]);
      break;
    case ColmapModel::Radial:
      cam.fx = cam.fy = float(p[0]), cam.cx = float(p[1]), cam.cy = float(p[2]);
      cam.dist.k1 = float(p[3]), cam.dist.k2 = float(p[4]);
      break;
    case ColmapModel::OpenCV:
      cam.fx = float(p[0]), cam.fy = float(p[1]), cam.cx = float(p[2]), cam.cy = float(p[3]);
      cam.dist.k1 = float(p[4]), cam.dist.k2 = float(p[5]), cam.dist.p1 = float(p[6]), cam.dist.p2 = float(p[7]);
      break;
  }
  return cam;
}

}  // namespace

Dataset load_colmap(const fs::path& root, const fs::path& sparse, const DatasetOptions& options) {
  bool binary = false;
  ColmapSparseModel m = read_colmap_model(sparse, &binary);
  const fs::path images_file = sparse / (binary ? "images.bin" : "images.txt");
  Dataset d;
  d.format = binary ? "colmap-binary" : "colmap-text";
  d.root = root;
  d.source = sparse;
  if (m.images.empty()) throw Error(images_file.string(), "no images: the model has zero registered images");
  const fs::path image_dir = root / "images";
  std::error_code ec;
  if (!fs::is_directory(image_dir, ec))
    throw Error(image_dir.string(), "images folder not found (COLMAP expects images/ beside sparse/)");

  std::unordered_map<uint32_t, Camera> intrinsics;
  for (const auto& c : m.cameras) intrinsics.emplace(c.id, intrinsics_from_colmap(c));
  // File-name order, so that the every-N-th test split does not depend on COLMAP's registration order.
  std::sort(m.images.begin(), m.images.end(), [](const ColmapImage& a, const ColmapImage& b) { return a.name < b.name; });
  MaskFinder masks(root);
  std::vector<View> views;
  views.reserve(m.images.size());
  for (const auto& im : m.images) {
    const fs::path image = image_dir / im.name;
    if (!fs::is_regular_file(image, ec))
      throw Error(images_file.string(), "image " + std::to_string(im.id) + " ('" + im.name + "') not found: " +
                                            image.string());
    Camera cam = intrinsics.at(im.camera_id);
    set_pose_from_qt(cam, im.qvec, im.tvec);
    require_finite_camera(cam, images_file.string(), "image " + std::to_string(im.id) + " ('" + im.name + "')");
    cam = fit_camera_to_image(cam, probe_image_size(image), image, "camera " + std::to_string(im.camera_id) + " of " +
                                                                       (sparse / (binary ? "cameras.bin" : "cameras.txt")).string());
    views.push_back(make_view(cam, image, masks, options));
  }
  d.points.xyz.reserve(m.points.size());
  d.points.rgb.reserve(m.points.size());
  for (const auto& p : m.points) {
    d.points.xyz.emplace_back(float(p.xyz[0]), float(p.xyz[1]), float(p.xyz[2]));
    d.points.rgb.emplace_back(p.rgb[0] / 255.0f, p.rgb[1] / 255.0f, p.rgb[2] / 255.0f);
  }
  split_every_nth(std::move(views), options, d);
  require_views(d, images_file.string());
  return d;
}

}  // namespace loaders
}  // namespace goris
