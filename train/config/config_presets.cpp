#include "train/config/config_presets.h"

#include <algorithm>
#include <system_error>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/util/error.h"
#include "core/util/resource_paths.h"

namespace goris {

namespace fs = std::filesystem;

std::vector<fs::path> preset_dir_candidates() {
#ifdef GORIS_PRESET_DIR
  return resource_dir_candidates("GORIS_PRESET_DIR", GORIS_PRESET_DIR, "presets");
#else
  return resource_dir_candidates("GORIS_PRESET_DIR", nullptr, "presets");
#endif
}

fs::path find_preset_dir() {
  std::string tried;
  for (const fs::path& d : preset_dir_candidates()) {
    std::error_code ec;
    if (fs::is_directory(d, ec)) return d;
    tried += "\n  " + d.string();
  }
  throw Error("presets folder not found; looked in:" + tried + "\n(set GORIS_PRESET_DIR to resources/presets)");
}

namespace {

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".json" && e.is_regular_file(ec)) names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

bool names_a_file(const std::string& s) {
  return s.find('/') != std::string::npos || (s.size() > 5 && s.compare(s.size() - 5, 5, ".json") == 0);
}

}  // namespace

std::vector<std::string> config_preset_names() {
  try {
    return names_in(find_preset_dir());
  } catch (const Error&) {
    return {};
  }
}

ConfigPreset read_config_preset(const fs::path& file) {
  const std::string where = file.string();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_text_file(file));
  } catch (const nlohmann::json::exception& e) {
    throw Error(where, std::string("malformed JSON (") + e.what() + ")");
  }
  if (!j.is_object()) throw Error(where, "a preset is a JSON object with \"description\" and \"settings\"");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "description" && it.key() != "settings")
      throw Error(where, "unknown key '" + it.key() + "' (a preset has \"description\" and \"settings\")");
  if (!j.contains("description") || !j["description"].is_string() || j["description"].get<std::string>().empty())
    throw Error(where, "\"description\" must be a non-empty string");
  if (!j.contains("settings") || !j["settings"].is_object())
    throw Error(where, "\"settings\" must be an object of config.json keys and their values");
  ConfigPreset p;
  p.name = file.stem().string();
  p.file = file;
  p.description = j["description"].get<std::string>();
  for (auto it = j["settings"].begin(); it != j["settings"].end(); ++it)
    p.settings.push_back(it.key() + "=" + it.value().dump());
  // Keys and values checked now, on the defaults, so that a bad file is named before any data loads.
  TrainConfig check;
  apply_config_preset(p, check);
  check.validate(where);
  return p;
}

ConfigPreset load_config_preset(const std::string& name_or_file) {
  if (name_or_file.empty()) throw Error("--preset: no preset name or file given");
  if (names_a_file(name_or_file)) return read_config_preset(fs::absolute(name_or_file));
  const fs::path dir = find_preset_dir();
  const fs::path file = dir / (name_or_file + ".json");
  std::error_code ec;
  if (!fs::exists(file, ec)) {
    std::string known;
    for (const std::string& n : names_in(dir)) known += (known.empty() ? "" : ", ") + n;
    throw Error("--preset " + name_or_file + ": unknown preset (known: " + (known.empty() ? "none" : known) +
                "; in " + dir.string() + "; a preset file is given by its path)");
  }
  return read_config_preset(file);
}

void apply_config_preset(const ConfigPreset& preset, TrainConfig& config) {
  apply_config_overrides(preset.settings, config, preset.file.string());
}

}  // namespace goris
