#include "ui/shell/screenshot.h"

#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/io/image.h"
#include "core/util/error.h"
#include "ui/gl/gl_api.h"

namespace goris::ui {

namespace fs = std::filesystem;

fs::path layout_path_for(const fs::path& png) { return png.parent_path() / (png.stem().string() + ".layout.json"); }

void save_screenshot(const fs::path& png, int w, int h, const std::vector<ViewportRecord>& viewports) {
  if (w <= 0 || h <= 0) throw Error(png.string(), "the window has no pixels to save");
  if (!png.parent_path().empty()) {
    std::error_code ec;
    fs::create_directories(png.parent_path(), ec);
    if (ec) throw Error(png.parent_path().string(), "cannot create the folder: " + ec.message());
  }
  std::vector<std::uint8_t> rgba(size_t(w) * size_t(h) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  check_gl("reading the window's pixels");
  Image img(w, h, 3, Device::CPU);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* row = rgba.data() + size_t(h - 1 - y) * size_t(w) * 4;  // GL rows start at the bottom
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.pixels[(size_t(y) * w + x) * 3 + c] = float(row[x * 4 + c]) / 255.0f;
  }
  save_png(png, img);

  nlohmann::json j;
  j["width"] = w;
  j["height"] = h;
  j["viewports"] = nlohmann::json::array();
  for (const ViewportRecord& v : viewports)
    j["viewports"].push_back({{"name", v.name},
                              {"channel", v.channel},
                              {"x", v.image.x},
                              {"y", v.image.y},
                              {"w", v.image.w},
                              {"h", v.image.h}});
  const fs::path layout = layout_path_for(png), tmp = layout.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(tmp.string(), "cannot be written");
    out << j.dump(2) << "\n";
    if (!out) throw Error(tmp.string(), "write failed");
  }
  std::error_code ec;
  fs::rename(tmp, layout, ec);
  if (ec) throw Error(layout.string(), "cannot be replaced: " + ec.message());
}

}  // namespace goris::ui
