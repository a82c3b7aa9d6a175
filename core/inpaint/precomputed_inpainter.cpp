#include "core/inpaint/precomputed_inpainter.h"

#include <system_error>

#include "core/inpaint/external_inpainter.h"
#include "core/inpaint/map_encoding.h"
#include "core/util/error.h"

namespace goris {

namespace fs = std::filesystem;

fs::path inpainted_file(const fs::path& dir, const MapInfo& info) {
  return dir / (file_safe(info.view) + "_" + file_safe(info.map) + ".png");
}

PrecomputedInpainter::PrecomputedInpainter(fs::path dir, std::shared_ptr<const Inpainter> fallback)
    : dir_(std::move(dir)), fallback_(std::move(fallback)) {
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) throw Error(dir_.string(), "not a folder of inpainted images");
}

std::string PrecomputedInpainter::name() const {
  return "inpainted images in " + dir_.string() + (fallback_ ? " (else " + fallback_->name() + ")" : "");
}

Image PrecomputedInpainter::fill(const Image& encoded, const Mask& hole, const MapInfo& info) const {
  const fs::path file = inpainted_file(dir_, info);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    if (fallback_) return fallback_->fill(encoded, hole, info);
    throw Error(file.string(), "no inpainted image for view " + info.view + ", map " + info.map +
                                   " (expected VIEW_MAP.png in " + dir_.string() + ")");
  }
  const Image got = read_image(file);
  if (got.width != encoded.width || got.height != encoded.height)
    throw Error(file.string(), "inpainted image is " + std::to_string(got.width) + "x" + std::to_string(got.height) +
                                   ", the view is " + std::to_string(encoded.width) + "x" +
                                   std::to_string(encoded.height));
  return adapt_channels(got, encoded);
}

}  // namespace goris
