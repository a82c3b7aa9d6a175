// NeRF-synthetic folders: transforms_train.json and transforms_test.json (camera_angle_x, Blender
// camera-to-world matrices, file paths usually without extension), RGBA images.
#include <system_error>

#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris::loaders {
namespace fs = std::filesystem;

namespace {
std::vector<View> load_split(const fs::path& json, const fs::path& root, MaskFinder& masks,
                             const DatasetOptions& options) {
  const TransformsFile tf = load_transforms_json(json);
  std::vector<View> views;
  views.reserve(tf.frames.size());
  for (size_t i = 0; i < tf.frames.size(); ++i) {
    const TransformsFrame& f = tf.frames[i];
    const std::string what = "frame " + std::to_string(i) + " ('" + f.file_path + "')";
    const fs::path image = find_image_file(json.parent_path() / f.file_path);
    if (image.empty())
      throw Error(json.string(), what + ": image not found (looked for " + (json.parent_path() / f.file_path).string() +
                                     " with and without .png/.jpg)");
    const TransformsIntrinsics in = tf.intrinsics.overridden_by(f.intrinsics);
    const Camera cam = camera_from_transforms(in, f.c2w, probe_image_size(image), image, json.string(), what);
    views.push_back(make_view(cam, image, masks, options));
  }
  return views;
}
}  // namespace

Dataset load_nerf_synthetic(const fs::path& root, const DatasetOptions& options) {
  Dataset d;
  d.format = "nerf-synthetic";
  d.root = root;
  d.source = root / "transforms_train.json";
  MaskFinder masks(root);
  d.train = load_split(root / "transforms_train.json", root, masks, options);
  std::error_code ec;
  if (fs::exists(root / "transforms_test.json", ec))
    d.test = load_split(root / "transforms_test.json", root, masks, options);
  require_views(d, d.source.string());
  return d;
}

}  // namespace goris::loaders
