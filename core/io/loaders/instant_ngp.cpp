// instant-ngp transforms.json: one file for all frames, intrinsics in pixels (fl_x, fl_y, cx, cy, w, h)
// with OpenCV distortion (k1, k2, k3, p1, p2), file-level or per frame. Frames whose image is missing are
// skipped (capture tools often list frames that were later deleted), with one warning.
#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris::loaders {
namespace fs = std::filesystem;

Dataset load_instant_ngp(const fs::path& json, const DatasetOptions& options) {
  Dataset d;
  d.format = "instant-ngp";
  d.root = json.parent_path();
  d.source = json;
  const TransformsFile tf = load_transforms_json(json);
  MaskFinder masks(d.root);
  std::vector<View> views;
  size_t skipped = 0;
  std::string first_missing;
  for (size_t i = 0; i < tf.frames.size(); ++i) {
    const TransformsFrame& f = tf.frames[i];
    const fs::path image = find_image_file(d.root / f.file_path);
    if (image.empty()) {
      if (skipped++ == 0) first_missing = f.file_path;
      continue;
    }
    const std::string what = "frame " + std::to_string(i) + " ('" + f.file_path + "')";
    const TransformsIntrinsics in = tf.intrinsics.overridden_by(f.intrinsics);
    const Camera cam = camera_from_transforms(in, f.c2w, probe_image_size(image), image, json.string(), what);
    views.push_back(make_view(cam, image, masks, options));
  }
  if (views.empty() && skipped > 0)
    throw Error(json.string(), "no images: the images of all " + std::to_string(skipped) +
                                   " frames are missing (first: " + first_missing + ")");
  if (skipped > 0)
    d.warnings.push_back(json.string() + ": skipped " + std::to_string(skipped) + " of " +
                         std::to_string(tf.frames.size()) + " frames whose image is missing (first: " + first_missing +
                         ")");
  split_every_nth(std::move(views), options, d);
  require_views(d, json.string());
  return d;
}

}  // namespace goris::loaders
