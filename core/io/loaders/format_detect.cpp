// Which loader reads a path: the files present decide (a data set folder, or one of its camera files).
#include <cmath>
#include <system_error>

#include "core/io/dataset.h"
#include "core/io/loaders/camera_warnings.h"
#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris {
namespace fs = std::filesystem;

namespace {

struct Detected {
  std::string format;  // "nerf-synthetic", "instant-ngp", "colmap", "llff"
  fs::path root;       // the data set folder
  fs::path source;     // transforms.json (instant-ngp) or the sparse folder (COLMAP)
};

bool file_exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

bool has_colmap_model(const fs::path& dir) { return file_exists(dir / "cameras.bin") || file_exists(dir / "cameras.txt"); }

// root for a COLMAP sparse folder: the folder holding sparse/ (sparse/0 or sparse/), else the folder itself.
fs::path colmap_root(const fs::path& sparse) {
  const fs::path parent = sparse.parent_path();
  if (sparse.filename() == "sparse") return parent;
  if (parent.filename() == "sparse") return parent.parent_path();
  return parent;
}

Detected detect(const fs::path& path_in) {
  std::error_code ec;
  const fs::path path = fs::absolute(path_in, ec).lexically_normal();
  if (!fs::exists(path, ec)) throw Error(path_in.string(), "not found");
  if (fs::is_regular_file(path, ec)) {
    const std::string f = path.filename().string();
    const fs::path dir = path.parent_path();
    if (f == "transforms_train.json" || f == "transforms_test.json" || f == "transforms_val.json")
      return {"nerf-synthetic", dir, dir};
    if (f == "transforms.json") return {"instant-ngp", dir, path};
    if (f == "poses_bounds.npy") return {"llff", dir, path};
    if (f == "cameras.bin" || f == "images.bin" || f == "points3D.bin" || f == "cameras.txt" || f == "images.txt" ||
        f == "points3D.txt")
      return {"colmap", colmap_root(dir), dir};
    throw Error(path_in.string(), "not a data set file (expected transforms_train.json, transforms.json, "
                                  "poses_bounds.npy or a COLMAP cameras/images/points3D file)");
  }
  if (!fs::is_directory(path, ec)) throw Error(path_in.string(), "is neither a file nor a folder");
  if (file_exists(path / "transforms_train.json")) return {"nerf-synthetic", path, path};
  if (file_exists(path / "transforms.json")) return {"instant-ngp", path, path / "transforms.json"};
  if (file_exists(path / "poses_bounds.npy")) return {"llff", path, path / "poses_bounds.npy"};
  if (has_colmap_model(path / "sparse" / "0")) return {"colmap", path, path / "sparse" / "0"};
  if (has_colmap_model(path / "sparse")) return {"colmap", path, path / "sparse"};
  if (has_colmap_model(path)) return {"colmap", colmap_root(path), path};
  throw Error(path_in.string(),
              "no data set recognised: expected transforms_train.json (NeRF-synthetic), transforms.json "
              "(instant-ngp), poses_bounds.npy (LLFF) or sparse/0/cameras.bin|txt (COLMAP)");
}

}  // namespace

std::string detect_dataset_format(const fs::path& path) {
  const Detected d = detect(path);
  if (d.format != "colmap") return d.format;
  return file_exists(d.source / "cameras.bin") ? "colmap-binary" : "colmap-text";
}

Dataset load_dataset(const fs::path& path, const DatasetOptions& options) {
  if (!(options.downscale > 0) || !std::isfinite(options.downscale))
    throw Error("invalid downscale factor " + std::to_string(options.downscale) + " (must be > 0)");
  if (options.target_width < 0) throw Error("invalid target width " + std::to_string(options.target_width));
  if (options.test_every < 0) throw Error("invalid test hold-out " + std::to_string(options.test_every) + " (must be >= 0)");
  const Detected d = detect(path);
  Dataset ds = d.format == "nerf-synthetic" ? loaders::load_nerf_synthetic(d.root, options)
               : d.format == "instant-ngp"  ? loaders::load_instant_ngp(d.source, options)
               : d.format == "llff"         ? loaders::load_llff(d.root, options)
                                            : loaders::load_colmap(d.root, d.source, options);
  if (options.undistort)
    for (auto* views : {&ds.train, &ds.test})
      for (View& v : *views)
        if (v.camera.has_distortion()) v.lens = v.camera.dist, v.camera.dist = Distortion{};
  loaders::add_camera_warnings(ds);
  return ds;
}

}  // namespace goris
