#include "train/run/normal_prior.h"

#include <cctype>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "core/io/image.h"
#include "core/util/error.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> candidates(const fs::path& dir, const std::string& view) {
  std::string digits;
  for (char c : view)
    if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
  std::vector<std::string> stems = {view, "normal_" + view};
  if (!digits.empty()) stems.push_back("normal_" + digits);
  std::vector<fs::path> out;
  for (const auto& s : stems)
    for (const char* ext : {".exr", ".png"}) out.push_back(dir / (s + ext));
  return out;
}

}  // namespace

void load_normal_priors(const fs::path& dir, std::vector<TrainView>& views) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "the normal-prior folder does not exist");
  for (TrainView& v : views) {
    fs::path file;
    for (const fs::path& c : candidates(dir, v.name))
      if (fs::exists(c)) {
        file = c;
        break;
      }
    if (file.empty())
      throw Error(dir.string(), "no normal map for view " + v.name + " (looked for " + v.name + ".exr/.png and normal_" +
                                    v.name + ".exr/.png)");
    Image img = read_image(file);
    if (img.channels < 3) throw Error(file.string(), "a normal map needs 3 channels");
    if (img.width != v.camera.width || img.height != v.camera.height)
      img = resize_image(img, v.camera.width, v.camera.height);
    const bool encoded = file.extension() == ".png";
    const std::vector<float> px = img.pixels.to_host();
    const int w = v.camera.width, h = v.camera.height, ch = img.channels;
    const std::size_t hw = std::size_t(w) * h;
    v.normal_prior.assign(3 * hw, 0.0f);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(y) * w + x;
        glm::vec3 n(px[p * ch], px[p * ch + 1], px[p * ch + 2]);
        if (encoded) n = n * 2.0f - 1.0f;
        if (!std::isfinite(n.x + n.y + n.z) || glm::length(n) < 0.1f) continue;
        glm::vec3 c = glm::normalize(v.camera.R * n);
        // Facing the camera: the pixel's viewing ray in camera space is (x_n, y_n, 1).
        const glm::vec3 ray((x + 0.5f - v.camera.cx) / v.camera.fx, (y + 0.5f - v.camera.cy) / v.camera.fy, 1.0f);
        if (glm::dot(c, ray) > 0) c = -c;
        for (int k = 0; k < 3; ++k) v.normal_prior[k * hw + p] = c[k];
      }
  }
}

}  // namespace goris
