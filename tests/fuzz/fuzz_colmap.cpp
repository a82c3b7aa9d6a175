// libFuzzer target for the COLMAP model parsers. The first byte picks the parser (cameras / images /
// points3D, binary or text), the rest is the file. Any input must parse or throw goris::Error; anything
// else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/io/loaders/colmap_model.h"
#include "core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t which = data[0] % 6;
  const uint8_t* p = data + 1;
  const size_t n = size - 1;
  const std::string_view text(reinterpret_cast<const char*>(p), n);
  try {
    switch (which) {
      case 0: {
        for (const auto& c : goris::parse_colmap_cameras_bin(p, n, "cameras.bin"))
          if (c.params.size() != size_t(goris::colmap_param_count(int(c.model)))) std::abort();
        break;
      }
      case 1: goris::parse_colmap_images_bin(p, n, "images.bin"); break;
      case 2: goris::parse_colmap_points3d_bin(p, n, "points3D.bin"); break;
      case 3: {
        for (const auto& c : goris::parse_colmap_cameras_txt(text, "cameras.txt"))
          if (c.params.size() != size_t(goris::colmap_param_count(int(c.model)))) std::abort();
        break;
      }
      case 4: goris::parse_colmap_images_txt(text, "images.txt"); break;
      default: goris::parse_colmap_points3d_txt(text, "points3D.txt"); break;
    }
  } catch (const goris::Error&) {
  }
  return 0;
}
