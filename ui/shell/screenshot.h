#pragma once
// Screenshots of the whole window (the scripted mode's `screenshot PATH`): the default framebuffer read
// back as PNG, and beside it <stem>.layout.json with every viewport's image rectangle (in screenshot
// pixels, origin top-left) and channel, so tests can check each tile.
#include <filesystem>
#include <string>
#include <vector>

#include "ui/document/panel_layout.h"

namespace goris::ui {

struct ViewportRecord {
  std::string name;     // "main", "grid0", ...
  std::string channel;  // channel id
  Rect image;           // screenshot pixels
};

std::filesystem::path layout_path_for(const std::filesystem::path& png);

// Reads fb_width x fb_height pixels of the current read framebuffer (call after drawing, before the swap)
// and writes the PNG and the layout file, each through a temporary file. Throws goris::Error naming the file.
void save_screenshot(const std::filesystem::path& png, int fb_width, int fb_height,
                     const std::vector<ViewportRecord>& viewports);

}  // namespace goris::ui
