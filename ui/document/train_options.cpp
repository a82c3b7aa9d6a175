#include "ui/document/train_options.h"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <optional>

#include "core/util/error.h"
#include "train/config/config_presets.h"

namespace goris::ui {

namespace fs = std::filesystem;

void apply_config_override(TrainConfig& config, const std::string& key, const std::string& value) {
  if (key.empty()) throw Error("set: no setting name given");
  TrainConfig updated = config;
  apply_config_overrides({key + "=" + value}, updated, "set");  // core's parser: unknown and removed keys named
  try {
    updated.validate("value");
  } catch (const std::exception& e) {
    throw Error("set " + key + " " + value + ": " + e.what());
  }
  config = std::move(updated);
}

TrainConfig new_run_config(const StudioSettings& s, const std::vector<std::pair<std::string, std::string>>& overrides) {
  TrainConfig c;
  const std::optional<TrainMode> mode = enum_from_name<TrainMode>(s.train_mode);
  if (!mode) throw Error("train_mode '" + s.train_mode + "' must be " + enum_choices<TrainMode>());
  c.mode = *mode;
  c.iterations = s.train_iterations;
  c.input.resolution = s.train_resolution;
  c.init.random_points = s.train_init_points;
  c.device = train_device_choice(s);
  c.input.background = s.train_white_background ? glm::vec3(1.0f) : glm::vec3(0.0f);
  if (!s.train_preset.empty()) apply_config_preset(load_config_preset(s.train_preset), c);  // as --preset: before
  for (const auto& [k, v] : overrides) apply_config_override(c, k, v);
  return c;
}

fs::path runs_root() {
  const char* xdg = std::getenv("XDG_DATA_HOME");
  if (xdg && *xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "goris-studio" / "runs";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".local" / "share" / "goris-studio" / "runs";
  return fs::current_path() / "goris-runs";
}

fs::path default_run_folder(const fs::path& dataset) {
  std::string name = fs::absolute(dataset).lexically_normal().filename().string();
  if (name.empty()) name = fs::absolute(dataset).lexically_normal().parent_path().filename().string();
  if (name.empty()) name = "run";
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&now, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
  fs::path p = runs_root() / (name + "-" + stamp);
  for (int k = 2; fs::exists(p); ++k) p = runs_root() / (name + "-" + stamp + "-" + std::to_string(k));
  return p;
}

}  // namespace goris::ui
