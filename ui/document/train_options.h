#pragma once
// The settings of a new training run as the editor builds them: the Training panel's fields, then any
// `set KEY VALUE` overrides (config.json keys, as `goris train --set`), and where the run folder goes when
// the user names none.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "train/config/train_config.h"
#include "ui/document/settings_store.h"

namespace goris::ui {

// Applies KEY=VALUE to `config` as `goris train --set KEY=VALUE` does (train/config/train_config.h), then
// validates it, so that a script or the panel fails at the line that sets a bad value. Throws goris::Error
// for an unknown or removed key or a value the configuration rejects.
void apply_config_override(TrainConfig& config, const std::string& key, const std::string& value);

// The panel's options (mode, iterations, resolution, initial points, device, background), its preset's
// settings (a preset file, train/config/config_presets.h, as `goris train --preset`), then `overrides` in order.
// Throws goris::Error naming the preset's file when it cannot be read.
TrainConfig new_run_config(const StudioSettings& settings,
                           const std::vector<std::pair<std::string, std::string>>& overrides);

// $XDG_DATA_HOME/goris-studio/runs (or ~/.local/share/goris-studio/runs).
std::filesystem::path runs_root();
// A fresh folder name under runs_root() for a data set: <data set folder name>-<YYYYmmdd-HHMMSS>.
std::filesystem::path default_run_folder(const std::filesystem::path& dataset);

}  // namespace goris::ui
