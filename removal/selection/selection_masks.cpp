#include "removal/selection/selection_masks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "removal/selection/selection_region.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

void check_settings(const MaskVoteSettings& s) {
  auto in01 = [](float v) { return v >= 0.0f && v <= 1.0f; };
  if (!in01(s.mask_threshold) || !in01(s.min_fraction) || !(s.min_fraction > 0.0f))
    throw Error("masks", "mask threshold must lie in [0, 1] and the view fraction in (0, 1]");
  if (s.min_views < 1) throw Error("masks", "min_views must be at least 1");
  if (!(s.depth_tolerance >= 0.0f)) throw Error("masks", "depth tolerance must be >= 0");
}

bool is_mask_extension(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".bmp" || e == ".tif" || e == ".tiff" || e == ".exr";
}

}  // namespace

MaskVotes labels_from_masks(const GaussianModel& model, const std::vector<MaskedView>& views,
                            const MaskVoteSettings& s, const RasterSettings& raster,
                            const std::function<void(std::size_t, std::size_t)>& on_view) {
  check_settings(s);
  if (views.empty()) throw Error("masks", "no view with an object mask to vote with");
  if (views.size() > 65535) throw Error("masks", "more than 65535 masked views");
  const std::size_t n = model.count();
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::vector<float> ls = model.tensor(Param::LogScale).value.to_host();
  std::vector<glm::vec3> centres(n);
  std::vector<float> sigma(n);
  for (std::size_t i = 0; i < n; ++i) {
    centres[i] = glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    sigma[i] = std::exp(std::max({ls[3 * i], ls[3 * i + 1], ls[3 * i + 2]}));
  }
  MaskVotes votes;
  votes.visible.assign(n, 0);
  votes.inside.assign(n, 0);
  votes.selected.assign(n, 0);

  for (const MaskedView& mv : views) {
    const Camera& cam = mv.camera;
    const int w = cam.width, h = cam.height;
    if (mv.mask.width != w || mv.mask.height != h || mv.mask.channels != 1 || mv.mask.pixels.device() != Device::CPU)
      throw Error(mv.name, "mask is " + std::to_string(mv.mask.width) + "x" + std::to_string(mv.mask.height) + "x" +
                               std::to_string(mv.mask.channels) + ", expected a one-channel CPU image of " +
                               std::to_string(w) + "x" + std::to_string(h));
    if (n == 0) continue;
    const std::vector<std::int32_t> px = visible_centre_pixels(model, centres, sigma, cam, raster, s.depth_tolerance);
    const float* mask = mv.mask.pixels.data();
    for (std::size_t i = 0; i < n; ++i) {
      if (px[i] < 0) continue;
      ++votes.visible[i];
      if (mask[px[i]] > s.mask_threshold) ++votes.inside[i];
    }
    ++votes.views;
    if (on_view) on_view(votes.views, views.size());
  }
  for (std::size_t i = 0; i < n; ++i)
    votes.selected[i] = votes.visible[i] >= s.min_views &&
                                float(votes.inside[i]) >= s.min_fraction * float(votes.visible[i])
                            ? 1
                            : 0;
  return votes;
}

std::vector<MaskedView> load_masked_views(const std::vector<View>& views, const std::optional<fs::path>& mask_dir) {
  std::map<std::string, fs::path> listing;  // stem -> file in mask_dir (sorted: deterministic on clashes)
  if (mask_dir) {
    std::error_code ec;
    if (!fs::is_directory(*mask_dir, ec)) throw Error(mask_dir->string(), "mask folder not found");
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(*mask_dir, ec))
      if (e.is_regular_file(ec) && is_mask_extension(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) listing.emplace(f.stem().string(), f);
  }
  std::vector<MaskedView> out;
  for (const View& v : views) {
    MaskedView mv;
    mv.name = v.name;
    mv.camera = v.camera;
    if (!mask_dir) {
      if (!v.object_mask) continue;
      mv.mask = load_view_object_mask(v, Device::CPU);
    } else {
      const std::string tail = v.name.rfind("r_", 0) == 0 ? v.name.substr(2) : v.name;
      auto it = listing.find("mask_" + tail);
      if (it == listing.end()) it = listing.find(v.name);
      if (it == listing.end()) continue;
      Image m = load_mask(it->second, Device::CPU);
      const bool source_size = m.width == v.source_width && m.height == v.source_height;
      const bool camera_size = m.width == v.camera.width && m.height == v.camera.height;
      if (!source_size && !camera_size)
        throw Error(it->second.string(), "is " + std::to_string(m.width) + "x" + std::to_string(m.height) +
                                             " but view " + v.name + " is " + std::to_string(v.source_width) + "x" +
                                             std::to_string(v.source_height));
      mv.mask = resize_image(m, v.camera.width, v.camera.height);
    }
    out.push_back(std::move(mv));
  }
  if (out.empty()) {
    if (mask_dir)
      throw Error(mask_dir->string(), "holds no mask for any of the " + std::to_string(views.size()) +
                                          " views (expected mask_XXX.png for r_XXX, or <view name>.png)");
    throw Error("masks", "none of the " + std::to_string(views.size()) +
                             " training views has an object mask (mask_XXX.png beside r_XXX.png, or masks/<name>.png)");
  }
  return out;
}

}  // namespace goris
