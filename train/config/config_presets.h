#pragma once
// Presets: named groups of training settings, one JSON file each (resources/presets/NAME.json), applied on
// top of a configuration before any `--set` line (`goris train --preset NAME|FILE`, the editor's preset
// chooser). A file holds a one-line description and the settings, keyed exactly as in a run's config.json:
//
//   {"description": "...", "settings": {"alpha_weight": 0.3, "intrinsic_glossy_plane": true}}
//
// The settings go through apply_config_overrides (train/config/train_config.h), so a preset and `--set` accept
// and refuse the same keys and values.
//
// The presets folder is found as the editor's shaders are (core/util/resource_paths.h): $GORIS_PRESET_DIR;
// the source tree's resources/presets (compiled in); presets/ next to the executable (the build copies them
// there); ../share/goris-studio/presets from the executable (an installed layout).
#include <filesystem>
#include <string>
#include <vector>

#include "train/config/train_config.h"

namespace goris {

struct ConfigPreset {
  std::string name;                   // the file's name without .json
  std::filesystem::path file;         // where it was read from
  std::string description;            // one line, for choosers and listings
  std::vector<std::string> settings;  // KEY=VALUE (VALUE as JSON), in key order
};

// The candidates for the presets folder in the order above (for messages and tests).
std::vector<std::filesystem::path> preset_dir_candidates();
// The first candidate that is a folder; throws goris::Error listing the places tried.
std::filesystem::path find_preset_dir();

// `name_or_file`: a preset's name (looked up as NAME.json in find_preset_dir()), or the path of a preset
// file (anything with a '/' or ending in .json). Reads and checks it: malformed JSON, a missing description
// or settings object, an unknown or removed setting and a value the setting refuses (alone on the defaults)
// are goris::Error naming the file. An unknown name lists the known ones.
ConfigPreset load_config_preset(const std::string& name_or_file);
// Reads a preset file (as above, for a path).
ConfigPreset read_config_preset(const std::filesystem::path& file);
// The names of the presets in find_preset_dir(), sorted; empty when no presets folder is found.
std::vector<std::string> config_preset_names();

// Applies the preset's settings to `config` through apply_config_overrides; errors name the preset's file.
void apply_config_preset(const ConfigPreset& preset, TrainConfig& config);

}  // namespace goris
