// What the editor remembers between sessions (ui/document/settings_store.h) and where runs go
// (ui/document/train_options.h): a round trip through the file, defaults for a missing file, errors naming the file
// and the key for a bad one, the XDG locations, and the training options built from the panel.
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "train/config/config_presets.h"
#include "ui/document/settings_store.h"
#include "ui/document/train_options.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

std::string load_error(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  try {
    load_settings(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace

TEST(StudioSettings, RoundTrip) {
  const fs::path dir = test::scratch_dir("studio_settings_rt");
  const fs::path file = dir / "sub" / "settings.json";
  EXPECT_EQ(load_settings(file).window_width, StudioSettings{}.window_width);  // missing: defaults
  StudioSettings s;
  s.window_width = 1600;
  s.window_height = 900;
  s.show_sidebar = false;
  s.show_debug_overlay = true;
  s.add_recent("/data/a");
  s.add_recent("/data/b");
  s.main_channel = "depth";
  s.grid_channels = {"normal", "alpha"};
  s.display_max_side = 300;
  s.compare_mode = "slider";
  s.train_mode = "intrinsic";
  s.train_iterations = 500;
  s.train_resolution = 64;
  s.train_init_points = 1234;
  s.train_device = "cpu";
  s.train_white_background = true;
  s.removal_inpainter = "cmd:lama {image} {mask} {out}";
  s.removal_iterations = 300;
  s.removal_ablate_material = true;
  s.removal_ablate_lamask = true;
  s.removal_absolute_fresnel = true;
  s.removal_ablate_twins = true;
  s.removal_ablate_shadows = true;
  save_settings(file, s);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  const StudioSettings r = load_settings(file);
  EXPECT_EQ(r.window_width, 1600);
  EXPECT_EQ(r.window_height, 900);
  EXPECT_FALSE(r.show_sidebar);
  EXPECT_TRUE(r.show_debug_overlay);
  EXPECT_EQ(r.recent_paths, (std::vector<std::string>{"/data/b", "/data/a"}));
  EXPECT_EQ(r.main_channel, "depth");
  EXPECT_EQ(r.grid_channels, (std::vector<std::string>{"normal", "alpha"}));
  EXPECT_EQ(r.display_max_side, 300);
  EXPECT_EQ(r.compare_mode, "slider");
  EXPECT_EQ(r.train_mode, "intrinsic");
  EXPECT_EQ(r.train_iterations, 500);
  EXPECT_EQ(r.train_resolution, 64);
  EXPECT_EQ(r.train_init_points, 1234);
  EXPECT_EQ(r.train_device, "cpu");
  EXPECT_TRUE(r.train_white_background);
  EXPECT_EQ(r.removal_inpainter, "cmd:lama {image} {mask} {out}");
  EXPECT_EQ(r.removal_iterations, 300);
  EXPECT_TRUE(r.removal_ablate_material);
  EXPECT_TRUE(r.removal_ablate_lamask);
  EXPECT_TRUE(r.removal_absolute_fresnel);
  EXPECT_TRUE(r.removal_ablate_twins);
  EXPECT_TRUE(r.removal_ablate_shadows);
}

TEST(StudioSettings, RecentPathsAreUniqueAndBounded) {
  StudioSettings s;
  for (int i = 0; i < 15; ++i) s.add_recent("/p" + std::to_string(i));
  ASSERT_EQ(s.recent_paths.size(), StudioSettings::kMaxRecent);
  EXPECT_EQ(s.recent_paths.front(), "/p14");
  s.add_recent("/p10");
  EXPECT_EQ(s.recent_paths.front(), "/p10");
  EXPECT_EQ(std::count(s.recent_paths.begin(), s.recent_paths.end(), "/p10"), 1);
  EXPECT_EQ(s.recent_paths.size(), StudioSettings::kMaxRecent);
}

TEST(StudioSettings, BadFilesNameTheProblem) {
  const fs::path f = test::scratch_dir("studio_settings_bad") / "settings.json";
  EXPECT_NE(load_error(f, "{ not json").find(f.string() + ": is not valid JSON"), std::string::npos);
  EXPECT_NE(load_error(f, "[1, 2]").find("must hold a JSON object"), std::string::npos);
  EXPECT_NE(load_error(f, R"({"window_width": "wide"})").find("'window_width' has the wrong type"), std::string::npos);
  EXPECT_NE(load_error(f, R"({"window_width": 10})").find("'window_width' = 10 is outside"), std::string::npos);
  EXPECT_NE(load_error(f, R"({"main_channel": "sparkle"})").find("unknown channel 'sparkle'"), std::string::npos);
  EXPECT_NE(load_error(f, R"({"grid_channels": ["depth", 3]})").find("'grid_channels' has the wrong type"),
            std::string::npos);
  EXPECT_NE(load_error(f, R"({"compare_mode": "wipe"})").find("'compare_mode': unknown value 'wipe'"),
            std::string::npos);
  EXPECT_NE(load_error(f, R"({"train_device": "tpu"})").find("'train_device'"), std::string::npos);
  EXPECT_NE(load_error(f, R"({"train_mode": "fast"})").find("'train_mode': unknown value 'fast'"), std::string::npos);
  EXPECT_NE(load_error(f, R"({"removal_iterations": -5})").find("'removal_iterations' = -5 is outside"),
            std::string::npos);
  // Keys of other versions are ignored; what is known is read.
  EXPECT_EQ(load_error(f, R"({"future_key": 1, "display_max_side": 64})"), "");
  EXPECT_EQ(load_settings(f).display_max_side, 64);
}

TEST(StudioSettings, TheInpaintersDefaultFollowsTheRemoval) {
  const fs::path f = test::scratch_dir("studio_settings_inpainter") / "settings.json";
  EXPECT_EQ(StudioSettings{}.removal_inpainter, "") << "the default is the removal's own";
  save_settings(f, StudioSettings{});
  EXPECT_EQ(load_settings(f).removal_inpainter, "");
  // Editors that wrote no settings_version stored their default by name: telea, later harmonic.
  for (const char* old_default : {"telea", "harmonic"}) {
    EXPECT_EQ(load_error(f, std::string(R"({"removal_inpainter": ")") + old_default + R"("})"), "");
    EXPECT_EQ(load_settings(f).removal_inpainter, "") << old_default;
  }
  EXPECT_EQ(load_error(f, R"({"removal_inpainter": "ns"})"), "");
  EXPECT_EQ(load_settings(f).removal_inpainter, "ns") << "any other name was a choice";
  // A file of this version keeps a choice of the old default.
  StudioSettings chosen;
  chosen.removal_inpainter = "telea";
  save_settings(f, chosen);
  EXPECT_EQ(load_settings(f).removal_inpainter, "telea");
}

TEST(StudioSettings, FollowsXdgFolders) {
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", "/tmp/xdg_config_test");
    EXPECT_EQ(settings_path(), fs::path("/tmp/xdg_config_test/goris-studio/settings.json"));
  }
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", "");
    ScopedEnv home("HOME", "/tmp/home_test");
    EXPECT_EQ(settings_dir(), fs::path("/tmp/home_test/.config/goris-studio"));
    EXPECT_EQ(runs_root(), fs::path("/tmp/home_test/.local/share/goris-studio/runs"));
  }
  const fs::path data = test::scratch_dir("studio_settings_xdg");
  ScopedEnv xdg_data("XDG_DATA_HOME", data.string());
  const fs::path run = default_run_folder("/some/where/lego");
  EXPECT_EQ(run.parent_path(), data / "goris-studio" / "runs");
  EXPECT_EQ(run.filename().string().rfind("lego-", 0), 0u) << run;
  fs::create_directories(run);
  EXPECT_NE(default_run_folder("/some/where/lego"), run);  // never an existing folder
}

TEST(StudioSettings, TrainingOptionsOfANewRun) {
  StudioSettings s;
  s.train_iterations = 77;
  s.train_resolution = 48;
  s.train_init_points = 999;
  s.train_device = "cpu";
  s.train_white_background = true;
  s.train_mode = "auto";
  TrainConfig c = new_run_config(s, {{"seed", "5"}, {"lambda_ssim", "0.5"}, {"random_init_points", "123"}});
  EXPECT_EQ(c.mode, TrainMode::Auto);
  EXPECT_EQ(c.iterations, 77);
  EXPECT_EQ(c.input.resolution, 48);
  EXPECT_EQ(c.init.random_points, 123);  // the override wins over the panel
  EXPECT_EQ(c.device, DeviceChoice::CPU);
  EXPECT_EQ(c.seed, 5u);
  EXPECT_FLOAT_EQ(c.loss.lambda_ssim, 0.5f);
  EXPECT_EQ(c.input.background, glm::vec3(1.0f));
  apply_config_override(c, "background", "[0.5, 0.25, 0]");
  EXPECT_EQ(c.input.background, glm::vec3(0.5f, 0.25f, 0.0f));
  EXPECT_THROW(apply_config_override(c, "no_such_key", "1"), Error);
  EXPECT_THROW(apply_config_override(c, "iterations", "\"many\""), Error);
  EXPECT_THROW(apply_config_override(c, "iterations", "-5"), Error);  // validate() rejects it
  EXPECT_THROW(apply_config_override(c, "", "1"), Error);
  EXPECT_EQ(c.iterations, 77);  // failed overrides change nothing
}

// The Training panel's preset: the settings of `goris train --preset` on top of the panel's fields, a
// script's `set` lines on top of both; kept in settings.json, an unknown name there is refused by name.
TEST(StudioSettings, PresetOfANewRun) {
  StudioSettings s;
  s.train_mode = "intrinsic";
  s.train_preset = "planar-glossy";
  TrainConfig c = new_run_config(s, {{"intrinsic_env_distance", "1.2"}});
  EXPECT_EQ(c.mode, TrainMode::Intrinsic);
  EXPECT_TRUE(c.intrinsic.glossy_plane);
  EXPECT_FLOAT_EQ(c.loss.alpha_weight, 0.3f);
  EXPECT_FLOAT_EQ(c.intrinsic.env_distance, 1.2f);  // the override wins over the preset
  // The same run as the panel's fields with `goris train --preset planar-glossy`.
  TrainConfig by_cli = new_run_config(StudioSettings{}, {});
  by_cli.mode = TrainMode::Intrinsic;
  apply_config_preset(load_config_preset("planar-glossy"), by_cli);
  EXPECT_EQ(nlohmann::json(new_run_config(s, {})).dump(), nlohmann::json(by_cli).dump());
  const fs::path dir = test::scratch_dir("studio_settings_preset");
  save_settings(dir / "settings.json", s);
  EXPECT_EQ(load_settings(dir / "settings.json").train_preset, "planar-glossy");
  std::ofstream(dir / "bad.json") << "{\"train_preset\": \"shiny\"}";
  test::expect_error([&] { load_settings(dir / "bad.json"); }, "unknown preset 'shiny'");
}
