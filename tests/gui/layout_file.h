#pragma once
// The .layout.json beside an editor screenshot (ui/shell/screenshot.h): every viewport's image rectangle and
// channel. Shared by the GUI tests' checking tools.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

namespace goris::test {

// Reads PNG's layout (same folder, <stem>.layout.json); throws std::runtime_error naming the file.
inline nlohmann::json read_layout(const std::filesystem::path& png) {
  const std::filesystem::path path = png.parent_path() / (png.stem().string() + ".layout.json");
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": missing");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json layout = nlohmann::json::parse(text.str(), nullptr, false);
  if (layout.is_discarded() || !layout.contains("viewports"))
    throw std::runtime_error(path.string() + ": not a screenshot layout");
  return layout;
}

}  // namespace goris::test
