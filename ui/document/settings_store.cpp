#include "ui/document/settings_store.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/util/error.h"
#include "render/maps/channels.h"
#include "train/config/config_presets.h"

namespace goris::ui {

namespace fs = std::filesystem;
using nlohmann::json;

void StudioSettings::add_recent(const std::string& path) {
  std::erase(recent_paths, path);
  recent_paths.insert(recent_paths.begin(), path);
  if (recent_paths.size() > kMaxRecent) recent_paths.resize(kMaxRecent);
}

fs::path settings_dir() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg && *xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "goris-studio";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".config" / "goris-studio";
  return fs::current_path() / ".goris-studio";  // no home at all (a bare container): next to the work dir
}

fs::path settings_path() { return settings_dir() / "settings.json"; }

namespace {

template <class T>
void read_key(const json& j, const char* key, T& out, const fs::path& file) {
  if (!j.contains(key)) return;
  try {
    out = j.at(key).get<T>();
  } catch (const json::exception&) {
    throw Error(file.string(), std::string("'") + key + "' has the wrong type (" + j.at(key).dump() + ")");
  }
}

void check_range(int v, int lo, int hi, const char* key, const fs::path& file) {
  if (v < lo || v > hi)
    throw Error(file.string(), std::string("'") + key + "' = " + std::to_string(v) + " is outside " +
                                   std::to_string(lo) + ".." + std::to_string(hi));
}

void check_channel(const std::string& id, const char* key, const fs::path& file) {
  if (!channel_from_id(id))
    throw Error(file.string(), std::string("'") + key + "': unknown channel '" + id + "' (" + channel_id_list() + ")");
}

void check_member(const std::string& v, std::initializer_list<const char*> allowed, const char* key,
                  const fs::path& file) {
  for (const char* a : allowed)
    if (v == a) return;
  throw Error(file.string(), std::string("'") + key + "': unknown value '" + v + "'");
}

// A value that names one of a named enumeration's values (core/util/named_enum.h).
template <class E>
void check_name(const std::string& v, const char* key, const fs::path& file) {
  if (!enum_from_name<E>(v)) throw Error(file.string(), std::string("'") + key + "': unknown value '" + v + "'");
}

}  // namespace

StudioSettings load_settings(const fs::path& path) {
  StudioSettings s;
  if (!fs::exists(path)) return s;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  const json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded()) throw Error(path.string(), "is not valid JSON");
  if (!j.is_object()) throw Error(path.string(), "must hold a JSON object");
  read_key(j, "window_width", s.window_width, path);
  read_key(j, "window_height", s.window_height, path);
  read_key(j, "show_sidebar", s.show_sidebar, path);
  read_key(j, "show_grid", s.show_grid, path);
  read_key(j, "show_plots", s.show_plots, path);
  read_key(j, "show_debug_overlay", s.show_debug_overlay, path);
  read_key(j, "recent_paths", s.recent_paths, path);
  read_key(j, "main_channel", s.main_channel, path);
  read_key(j, "grid_channels", s.grid_channels, path);
  read_key(j, "display_max_side", s.display_max_side, path);
  read_key(j, "compare_mode", s.compare_mode, path);
  read_key(j, "train_mode", s.train_mode, path);
  read_key(j, "train_preset", s.train_preset, path);
  read_key(j, "train_iterations", s.train_iterations, path);
  read_key(j, "train_resolution", s.train_resolution, path);
  read_key(j, "train_init_points", s.train_init_points, path);
  read_key(j, "train_device", s.train_device, path);
  read_key(j, "train_white_background", s.train_white_background, path);
  read_key(j, "removal_inpainter", s.removal_inpainter, path);
  read_key(j, "removal_iterations", s.removal_iterations, path);
  read_key(j, "removal_ablate_material", s.removal_ablate_material, path);
  read_key(j, "removal_ablate_lamask", s.removal_ablate_lamask, path);
  read_key(j, "removal_ablate_twins", s.removal_ablate_twins, path);
  read_key(j, "removal_ablate_shadows", s.removal_ablate_shadows, path);
  read_key(j, "removal_absolute_fresnel", s.removal_absolute_fresnel, path);
  read_key(j, "removal_exclude_reflections", s.removal_exclude_reflections, path);
  read_key(j, "export_ply", s.export_ply, path);
  read_key(j, "export_baked", s.export_baked, path);
  read_key(j, "export_renders", s.export_renders, path);
  read_key(j, "export_ply_path", s.export_ply_path, path);
  read_key(j, "export_baked_path", s.export_baked_path, path);
  read_key(j, "export_renders_dir", s.export_renders_dir, path);
  read_key(j, "export_baked_iterations", s.export_baked_iterations, path);
  read_key(j, "export_baked_spz", s.export_baked_spz, path);
  read_key(j, "export_baked_compressed_ply", s.export_baked_compressed_ply, path);
  read_key(j, "export_baked_splat", s.export_baked_splat, path);
  read_key(j, "export_baked_glb", s.export_baked_glb, path);
  read_key(j, "export_render_path", s.export_render_path, path);
  read_key(j, "export_frames", s.export_frames, path);

  check_range(s.window_width, 320, 16384, "window_width", path);
  check_range(s.window_height, 240, 16384, "window_height", path);
  check_range(s.display_max_side, 32, 8192, "display_max_side", path);
  check_range(s.train_iterations, 1, 10000000, "train_iterations", path);
  check_range(s.train_resolution, 0, 16384, "train_resolution", path);
  check_range(s.train_init_points, 1, 100000000, "train_init_points", path);
  check_range(int(s.grid_channels.size()), 0, 8, "grid_channels (count)", path);
  check_range(s.removal_iterations, 0, 10000000, "removal_iterations", path);
  check_range(s.export_baked_iterations, 1, 10000000, "export_baked_iterations", path);
  check_range(s.export_frames, 0, 100000, "export_frames", path);
  check_member(s.export_render_path, {"test", "train", "orbit"}, "export_render_path", path);
  int version = 1;
  read_key(j, "settings_version", version, path);
  if (version < 2 && (s.removal_inpainter == "telea" || s.removal_inpainter == "harmonic")) s.removal_inpainter.clear();
  check_channel(s.main_channel, "main_channel", path);
  for (const std::string& c : s.grid_channels) check_channel(c, "grid_channels", path);
  check_member(s.compare_mode, {"off", "side_by_side", "slider"}, "compare_mode", path);
  check_name<DeviceChoice>(s.train_device, "train_device", path);
  check_name<TrainMode>(s.train_mode, "train_mode", path);
  // A preset's name must be one of the presets folder's; a preset file (a path) is read when a run starts.
  const std::vector<std::string> presets = config_preset_names();
  if (!s.train_preset.empty() && s.train_preset.find('/') == std::string::npos && !s.train_preset.ends_with(".json") &&
      std::find(presets.begin(), presets.end(), s.train_preset) == presets.end())
    throw Error(path.string(), "'train_preset': unknown preset '" + s.train_preset + "'");
  if (s.recent_paths.size() > StudioSettings::kMaxRecent) s.recent_paths.resize(StudioSettings::kMaxRecent);
  return s;
}

void save_settings(const fs::path& path, const StudioSettings& s) {
  const json j = {{"settings_version", 2},
                  {"window_width", s.window_width},
                  {"window_height", s.window_height},
                  {"show_sidebar", s.show_sidebar},
                  {"show_grid", s.show_grid},
                  {"show_plots", s.show_plots},
                  {"show_debug_overlay", s.show_debug_overlay},
                  {"recent_paths", s.recent_paths},
                  {"main_channel", s.main_channel},
                  {"grid_channels", s.grid_channels},
                  {"display_max_side", s.display_max_side},
                  {"compare_mode", s.compare_mode},
                  {"train_mode", s.train_mode},
                  {"train_preset", s.train_preset},
                  {"train_iterations", s.train_iterations},
                  {"train_resolution", s.train_resolution},
                  {"train_init_points", s.train_init_points},
                  {"train_device", s.train_device},
                  {"train_white_background", s.train_white_background},
                  {"removal_inpainter", s.removal_inpainter},
                  {"removal_iterations", s.removal_iterations},
                  {"removal_ablate_material", s.removal_ablate_material},
                  {"removal_ablate_lamask", s.removal_ablate_lamask},
                  {"removal_ablate_twins", s.removal_ablate_twins},
                  {"removal_ablate_shadows", s.removal_ablate_shadows},
                  {"removal_absolute_fresnel", s.removal_absolute_fresnel},
                  {"removal_exclude_reflections", s.removal_exclude_reflections},
                  {"export_ply", s.export_ply},
                  {"export_baked", s.export_baked},
                  {"export_renders", s.export_renders},
                  {"export_ply_path", s.export_ply_path},
                  {"export_baked_path", s.export_baked_path},
                  {"export_renders_dir", s.export_renders_dir},
                  {"export_baked_iterations", s.export_baked_iterations},
                  {"export_baked_spz", s.export_baked_spz},
                  {"export_baked_compressed_ply", s.export_baked_compressed_ply},
                  {"export_baked_splat", s.export_baked_splat},
                  {"export_baked_glb", s.export_baked_glb},
                  {"export_render_path", s.export_render_path},
                  {"export_frames", s.export_frames}};
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw Error(path.parent_path().string(), "cannot create the folder: " + ec.message());
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(tmp.string(), "cannot be written");
    out << j.dump(2) << "\n";
    if (!out) throw Error(tmp.string(), "write failed");
  }
  fs::rename(tmp, path, ec);
  if (ec) throw Error(path.string(), "cannot be replaced: " + ec.message());
}

}  // namespace goris::ui
