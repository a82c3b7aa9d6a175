#pragma once
// What the editor remembers between sessions (window size, panels, recent paths, channel choices,
// training options), as JSON in $XDG_CONFIG_HOME/goris-studio/settings.json (~/.config/... without it).
#include <filesystem>
#include <string>
#include <vector>

#include "core/compute/device_choice.h"

namespace goris::ui {

struct StudioSettings {
  int window_width = 1280, window_height = 800;
  bool show_sidebar = true, show_grid = true, show_plots = true, show_debug_overlay = false;
  std::vector<std::string> recent_paths;  // most recent first, at most kMaxRecent
  std::string main_channel = "final";
  std::vector<std::string> grid_channels{"diffuse", "normal", "depth", "roughness"};
  int display_max_side = 512;        // viewport renders are capped at this many pixels on their longest side
  std::string compare_mode = "off";  // off | side_by_side | slider
  // Training options of the panel (a new run; a resumed run keeps its own).
  std::string train_mode = "auto";  // radiance | intrinsic | auto (as `goris train --mode`)
  std::string train_preset;             // "" or a preset's name or file (as `goris train --preset`)
  int train_iterations = 3000;
  int train_resolution = 0;       // 0 = the data set's size
  int train_init_points = 20000;  // random initial points when the data has no SfM points
  std::string train_device = "auto";  // auto | cpu | cuda (as `goris train --device`)
  bool train_white_background = false;  // composite RGBA photos on white instead of black
  // Removal options of the panel (as `goris remove`).
  // "" = the removal's default (RemovalOptions::inpainter), so a saved file follows a changed default; else a
  // choice: harmonic | telea | ns | fsr | cmd:COMMAND.
  std::string removal_inpainter;
  int removal_iterations = 0;               // fine-tune iterations; 0 = the pipeline's default
  bool removal_ablate_material = false;     // RGB-only inpainting
  bool removal_ablate_lamask = false;       // no lighting-aware mask
  bool removal_ablate_twins = false;        // keep the target's mirror twin
  bool removal_ablate_shadows = false;      // keep the target's cast shadow
  bool removal_absolute_fresnel = false;    // the paper's absolute F in the lighting-aware mask
  bool removal_exclude_reflections = false; // the paper's rule: no photo loss in the lighting-aware mask
  // Export dialog (as `goris export`): which parts, where (relative paths lie inside the exported run
  // folder, absolute ones are used as they are), the distillation length and the render cameras.
  bool export_ply = true, export_baked = false, export_renders = false;
  std::string export_ply_path = "export/model.ply";
  std::string export_baked_path = "export/baked.ply";
  std::string export_renders_dir = "export/renders";
  int export_baked_iterations = 2000;
  // The baked model also as SPZ / compressed PLY / .splat / GLB, beside the baked PLY (ui/document/export_job.h).
  bool export_baked_spz = false, export_baked_compressed_ply = false, export_baked_splat = false,
       export_baked_glb = false;
  std::string export_render_path = "test";  // test | train | orbit
  int export_frames = 0;                    // orbit: frame count (0 = 36); test / train: views (0 = all)

  static constexpr size_t kMaxRecent = 10;
  // Moves `path` to the front of the recent list (no duplicates, at most kMaxRecent).
  void add_recent(const std::string& path);
};

// The training device the settings name (checked when they are read, so never an unknown name).
inline DeviceChoice train_device_choice(const StudioSettings& s) {
  return enum_from_name<DeviceChoice>(s.train_device).value_or(DeviceChoice::Auto);
}

// $XDG_CONFIG_HOME/goris-studio, or $HOME/.config/goris-studio.
std::filesystem::path settings_dir();
std::filesystem::path settings_path();

// Missing file: defaults. Malformed file or a value of the wrong type / out of range: goris::Error naming
// the file and the key. A file without "settings_version" (editors that stored the inpainter's default as
// a name) holding "telea" or "harmonic" reads as the default inpainter: those were the defaults it was saved
// with, and nothing told them from a choice.
StudioSettings load_settings(const std::filesystem::path& path);
// Writes through a temporary file renamed into place; creates the folder.
void save_settings(const std::filesystem::path& path, const StudioSettings& settings);

}  // namespace goris::ui
