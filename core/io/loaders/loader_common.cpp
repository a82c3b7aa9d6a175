#include "core/io/loaders/loader_common.h"

#include <algorithm>
#include <cmath>
#include <system_error>

#include "core/util/error.h"

namespace goris::loaders {
namespace fs = std::filesystem;

void set_pose_from_c2w(Camera& cam, const glm::dmat3& c2w, const glm::dvec3& center, const std::string& file,
                       const std::string& what) {
  // Orthonormal with det +1 up to the rounding of text files; larger deviations are data errors.
  const glm::dmat3 should_be_identity = glm::transpose(c2w) * c2w;
  double err = 0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) err = std::max(err, std::abs(should_be_identity[c][r] - (r == c ? 1.0 : 0.0)));
  if (!(err < 1e-2)) throw Error(file, what + ": the rotation is not orthonormal (scaled or sheared pose)");
  if (glm::determinant(c2w) < 0) throw Error(file, what + ": the rotation is a reflection (determinant < 0)");
  // Gram-Schmidt so that renderers may rely on R^T = R^-1.
  glm::dvec3 x = glm::normalize(c2w[0]);
  glm::dvec3 y = glm::normalize(c2w[1] - glm::dot(c2w[1], x) * x);
  glm::dvec3 z = glm::cross(x, y);
  const glm::dmat3 r_w2c = glm::transpose(glm::dmat3(x, y, z));
  cam.R = glm::mat3(r_w2c);
  cam.t = glm::vec3(-(r_w2c * center));
}

void set_pose_from_qt(Camera& cam, const double q_in[4], const double t[3]) {
  const double n = std::sqrt(q_in[0] * q_in[0] + q_in[1] * q_in[1] + q_in[2] * q_in[2] + q_in[3] * q_in[3]);
  const double w = q_in[0] / n, x = q_in[1] / n, y = q_in[2] / n, z = q_in[3] / n;
  // Row-major rotation of a unit quaternion; glm stores [column][row].
  const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) cam.R[c][r] = float(m[r][c]);
  cam.t = glm::vec3(float(t[0]), float(t[1]), float(t[2]));
}

void require_finite_camera(const Camera& c, const std::string& file, const std::string& what) {
  const float intrinsics[] = {c.fx, c.fy, c.cx, c.cy, c.dist.k1, c.dist.k2, c.dist.k3, c.dist.p1, c.dist.p2};
  for (float v : intrinsics)
    if (!std::isfinite(v)) throw Error(file, what + ": intrinsics out of range (not finite in single precision)");
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(c.t[i]) || !std::isfinite(c.center()[i]))
      throw Error(file, what + ": camera position out of range (not finite in single precision)");
}

Camera fit_camera_to_image(const Camera& declared, ImageSize actual, const fs::path& image,
                           const std::string& camera_source) {
  if (declared.width == actual.width && declared.height == actual.height) return declared;
  const double sx = double(actual.width) / declared.width, sy = double(actual.height) / declared.height;
  if (std::abs(sx / sy - 1.0) > 0.01)
    throw Error(image.string(), "image is " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
                                    " but " + camera_source + " declares " + std::to_string(declared.width) + "x" +
                                    std::to_string(declared.height) + " for it (a different aspect ratio)");
  return declared.resized(actual.width, actual.height);
}

bool is_image_extension(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".exr" || e == ".tif" || e == ".tiff" ||
         e == ".bmp" || e == ".webp";
}

fs::path find_image_file(const fs::path& base) {
  std::error_code ec;
  if (base.has_extension() && is_image_extension(base) && fs::is_regular_file(base, ec)) return base;
  for (const char* ext : {".png", ".jpg", ".jpeg", ".PNG", ".JPG", ".JPEG"}) {
    fs::path p = base;
    p += ext;
    if (fs::is_regular_file(p, ec)) return p;
  }
  if (fs::is_regular_file(base, ec)) return base;
  return {};
}

const std::map<std::string, fs::path>& MaskFinder::listing(const fs::path& dir) {
  auto it = cache_.find(dir);
  if (it != cache_.end()) return it->second;
  std::map<std::string, fs::path> files;
  std::error_code ec;
  if (fs::is_directory(dir, ec)) {
    std::vector<fs::path> all;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.is_regular_file(ec) && is_image_extension(e.path())) all.push_back(e.path());
    std::sort(all.begin(), all.end());  // deterministic choice when two files share a stem
    for (const auto& p : all) files.emplace(p.stem().string(), p);
  }
  return cache_.emplace(dir, std::move(files)).first->second;
}

std::optional<fs::path> MaskFinder::find(const fs::path& dir, const std::string& stem) {
  const auto& l = listing(dir);
  auto it = l.find(stem);
  if (it == l.end()) return std::nullopt;
  return it->second;
}

void MaskFinder::attach(View& v) {
  const fs::path dir = v.image.parent_path();
  const std::string stem = v.image.stem().string();
  // GOR-IS / NeRF-synthetic layout: r_XXX.png with mask_XXX.png, gloss_XXX.png, full_XXX.png beside it.
  const std::string tail = stem.rfind("r_", 0) == 0 ? stem.substr(2) : stem;
  v.object_mask = find(dir, "mask_" + tail);
  v.glossy_mask = find(dir, "gloss_" + tail);
  v.full_image = stem != tail ? find(dir, "full_" + tail) : std::nullopt;
  // A masks folder in the data set: masks/<stem>.*, gloss/<stem>.*
  if (!v.object_mask) v.object_mask = find(root_ / "masks", stem);
  if (!v.glossy_mask) v.glossy_mask = find(root_ / "gloss", stem);

  for (const auto* p : {&v.object_mask, &v.glossy_mask, &v.full_image}) {
    if (!*p) continue;
    const ImageSize s = probe_image_size(**p);
    if (s.width != v.source_width || s.height != v.source_height)
      throw Error((*p)->string(), "is " + std::to_string(s.width) + "x" + std::to_string(s.height) + " but its image " +
                                      v.image.string() + " is " + std::to_string(v.source_width) + "x" +
                                      std::to_string(v.source_height));
  }
}

View make_view(const Camera& camera_at_file_size, const fs::path& image, MaskFinder& masks,
               const DatasetOptions& options) {
  View v;
  v.name = image.stem().string();
  v.image = image;
  v.source_width = camera_at_file_size.width;
  v.source_height = camera_at_file_size.height;
  masks.attach(v);
  const ImageSize s = scaled_size(v.source_width, v.source_height, options);
  v.camera = camera_at_file_size.resized(s.width, s.height);
  return v;
}

void split_every_nth(std::vector<View> views, const DatasetOptions& options, Dataset& out) {
  for (size_t i = 0; i < views.size(); ++i) {
    const bool test = options.test_every > 0 && i % size_t(options.test_every) == 0;
    (test ? out.test : out.train).push_back(std::move(views[i]));
  }
}

void require_views(const Dataset& d, const std::string& source) {
  if (d.view_count() == 0) throw Error(source, "no images: the data set has zero views");
}

}  // namespace goris::loaders
