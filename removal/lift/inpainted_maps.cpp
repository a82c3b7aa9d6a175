#include "removal/lift/inpainted_maps.h"

#include <vector>

#include "core/io/image.h"
#include "core/io/npy.h"
#include "core/io/npy_write.h"
#include "core/util/error.h"
#include "render/maps/gbuffer_maps.h"

namespace goris {

namespace {
namespace fs = std::filesystem;

void save_preview(const fs::path& path, const Image& im, const std::string& map) {
  const std::vector<float> px = im.pixels.to_host();
  const int w = im.width, h = im.height;
  const std::size_t hw = std::size_t(w) * h;
  if (map == "depth") {
    std::vector<float> alpha(hw);
    for (std::size_t p = 0; p < hw; ++p) alpha[p] = px[p] > 0 ? 1.0f : 0.0f;
    save_png(path, depth_to_turbo(px.data(), alpha.data(), w, h, false));
  } else if (map == "normal") {
    std::vector<float> planar(3 * hw), alpha(hw);
    for (std::size_t p = 0; p < hw; ++p) {
      for (int c = 0; c < 3; ++c) planar[c * hw + p] = px[p * 3 + c];
      alpha[p] = (px[p * 3] != 0 || px[p * 3 + 1] != 0 || px[p * 3 + 2] != 0) ? 1.0f : 0.0f;
    }
    save_png(path, normals_to_rgb(planar.data(), alpha.data(), w, h));
  } else {
    save_png(path, im);
  }
}

Image load_map(const fs::path& path) {
  const NpyArray a = load_npy(path);
  if (a.shape.size() != 3) throw Error(path.string(), "expected an [H][W][C] array");
  Image im(int(a.shape[1]), int(a.shape[0]), int(a.shape[2]));
  std::vector<float> px(a.data.begin(), a.data.end());
  im.pixels.upload(px.data(), px.size());
  return im;
}
}  // namespace

void save_inpainted_maps(const fs::path& dir, const std::string& stem, const MapSet& maps, bool previews) {
  for (const MapSlot& slot : map_slots()) {
    const Image& im = maps.*slot.member;
    if (im.pixels.size() == 0) continue;
    const std::string name = stem + "_" + slot.name;
    const std::vector<float> px = im.pixels.to_host();
    save_npy(dir / (name + ".npy"), px, {std::size_t(im.height), std::size_t(im.width), std::size_t(im.channels)});
    if (previews) save_preview(dir / (name + ".png"), im, slot.name);
  }
}

MapSet load_inpainted_maps(const fs::path& dir, const std::string& stem) {
  MapSet m;
  for (const MapSlot& slot : map_slots()) {
    const fs::path p = dir / (stem + "_" + slot.name + ".npy");
    if (fs::exists(p)) m.*slot.member = load_map(p);
  }
  return m;
}

bool inpainted_maps_present(const fs::path& dir, const std::string& stem) {
  for (const MapSlot& slot : map_slots())
    if (slot.member == &MapSet::rgb) return fs::exists(dir / (stem + "_" + slot.name + ".npy"));
  return false;
}

}  // namespace goris
