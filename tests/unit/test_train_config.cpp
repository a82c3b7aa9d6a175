// The training configuration's files: presets (resources/presets, train/config/config_presets.h), config.json
// of older versions (train/config/config_migration.h) and the user-facing settings' documentation.
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "tests/support/test_support.h"
#include "train/config/config_migration.h"
#include "train/config/config_presets.h"
#include "train/config/train_config.h"
#include "train/run/run_folder.h"

namespace goris {
namespace {

namespace fs = std::filesystem;

fs::path preset_folder() { return test::resource_dir() / "presets"; }
// config.json files written by older commits (tests/fixtures/config/config_<commit>.json: their to_json of
// the default configuration, with data, mode and iterations set).
fs::path old_config(const char* commit) {
  return test::resource_dir().parent_path() / "tests" / "fixtures" / "config" / ("config_" + std::string(commit) + ".json");
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// Every preset file of the source tree reads, describes itself and names only settings config.json has.
TEST(ConfigPresets, EveryPresetFileParsesAndItsKeysExist) {
  std::set<std::string> keys;
  for (const ConfigKeyInfo& k : config_keys()) keys.insert(k.key);
  size_t files = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(preset_folder())) {
    if (e.path().extension() != ".json") continue;
    ++files;
    SCOPED_TRACE(e.path().string());
    const ConfigPreset p = read_config_preset(e.path());
    EXPECT_EQ(p.name, e.path().stem().string());
    EXPECT_FALSE(p.description.empty());
    EXPECT_EQ(p.description.find('\n'), std::string::npos);
    EXPECT_FALSE(p.settings.empty());
    const nlohmann::json j = nlohmann::json::parse(read_text_file(e.path()));
    for (auto it = j["settings"].begin(); it != j["settings"].end(); ++it) EXPECT_TRUE(keys.count(it.key())) << it.key();
  }
  EXPECT_GE(files, 1u);
  // The source tree's folder is the one found (compiled in), and the chooser lists its files.
  EXPECT_EQ(fs::canonical(find_preset_dir()), fs::canonical(preset_folder()));
  EXPECT_EQ(config_preset_names().size(), files);
}

// planar-glossy: the measured stage-1 setting (docs/design/deviations.md, The glossy surface held to its
// plane), applied like --set lines: later --set lines win.
TEST(ConfigPresets, PlanarGlossySetsTheMeasuredSetting) {
  TrainConfig c;
  c.mode = TrainMode::Intrinsic;
  apply_config_preset(load_config_preset("planar-glossy"), c);
  EXPECT_FALSE(c.intrinsic.material_losses_in_warmup);
  EXPECT_EQ(c.loss.alpha_weight, 0.3f);
  EXPECT_TRUE(c.intrinsic.glossy_plane);
  EXPECT_TRUE(c.intrinsic.glossy_plane_prune_sinkers);
  EXPECT_TRUE(c.intrinsic.glossy_plane_align);
  EXPECT_EQ(c.intrinsic.trace_glossy_transparent, 0.5f);
  EXPECT_EQ(c.intrinsic.env_distance, 1.4f);
  EXPECT_NO_THROW(c.validate("preset"));
  // The same configuration as the --set lines the preset stands for.
  TrainConfig by_set;
  by_set.mode = TrainMode::Intrinsic;
  apply_config_overrides({"intrinsic_material_losses_in_warmup=false", "alpha_weight=0.3", "intrinsic_glossy_plane=true",
                          "intrinsic_glossy_plane_prune_sinkers=true", "intrinsic_trace_glossy_transparent=0.5",
                          "intrinsic_glossy_plane_align=true", "intrinsic_env_distance=1.4"},
                         by_set);
  EXPECT_EQ(nlohmann::json(c).dump(), nlohmann::json(by_set).dump());
  apply_config_overrides({"intrinsic_env_distance=1.2"}, c);
  EXPECT_EQ(c.intrinsic.env_distance, 1.2f);
}

TEST(ConfigPresets, UnknownNameListsTheKnownOnes) {
  test::expect_error([] { load_config_preset("shiny"); }, "unknown preset");
  test::expect_error([] { load_config_preset("shiny"); }, "planar-glossy");
}

// A preset given by its path; a bad one is refused naming the file and the problem.
TEST(ConfigPresets, FileByPathAndBadFiles) {
  const fs::path dir = test::scratch_dir("config_presets_files");
  write(dir / "mine.json", R"({"description": "mine", "settings": {"alpha_weight": 0.5, "intrinsic_emit": "max"}})");
  const ConfigPreset p = load_config_preset((dir / "mine.json").string());
  EXPECT_EQ(p.name, "mine");
  TrainConfig c;
  apply_config_preset(p, c);
  EXPECT_EQ(c.loss.alpha_weight, 0.5f);
  EXPECT_EQ(c.intrinsic.emit, EmitSource::Max);

  const auto refused = [&](const char* name, const std::string& text, const std::string& problem) {
    SCOPED_TRACE(name);
    write(dir / name, text);
    const std::string file = (dir / name).string();
    test::expect_error([&] { load_config_preset(file); }, file);
    test::expect_error([&] { load_config_preset(file); }, problem);
  };
  refused("malformed.json", R"({"description": "x", "settings": {"alpha_weight": 0.5,}})", "malformed JSON");
  refused("unknown.json", R"({"description": "x", "settings": {"alpha_wieght": 0.5}})", "unknown setting 'alpha_wieght'");
  refused("removed.json", R"({"description": "x", "settings": {"densify_stop": "adaptive"}})", "was removed");
  refused("type.json", R"({"description": "x", "settings": {"alpha_weight": "much"}})", "must be a number");
  refused("range.json", R"({"description": "x", "settings": {"lambda_ssim": 2}})", "lambda_ssim must lie in [0, 1]");
  refused("nodesc.json", R"({"settings": {"alpha_weight": 0.5}})", "\"description\"");
  refused("flat.json", R"({"description": "x", "alpha_weight": 0.5})", "unknown key 'alpha_weight'");
  refused("version.json", R"({"description": "x", "settings": {"config_version": 1}})", "not a setting");
  test::expect_error([&] { load_config_preset((dir / "absent.json").string()); }, (dir / "absent.json").string());
}

// config.json records its version; --set cannot change it; a newer one than this build's is refused.
TEST(ConfigMigration, VersionWrittenAndChecked) {
  const nlohmann::json j = TrainConfig{};
  EXPECT_EQ(j.at("config_version"), kConfigVersion);
  TrainConfig back;
  EXPECT_NO_THROW(from_json(j, back));
  test::expect_error([&] { apply_config_overrides({"config_version=1"}, back); }, "not a setting");
  nlohmann::json newer = j;
  newer["config_version"] = kConfigVersion + 1;
  test::expect_error([&] { from_json(newer, back); }, "newer than this build");
  newer["config_version"] = "2";
  test::expect_error([&] { from_json(newer, back); }, "whole number");
  // A version-2 file predates the colour rate's power: it reads as the fixed rate it trained with.
  nlohmann::json v2 = j;
  v2["config_version"] = 2;
  v2.erase("lr_sh_dc_short_run_power");
  from_json(v2, back);
  EXPECT_EQ(back.lr.sh_dc_short_run_power, 0.0f);
  EXPECT_GT(TrainConfig{}.lr.sh_dc_short_run_power, 0.0f);
}

// A run folder written at 46a5b55 (with 9 keys removed since: 3 stage-1 settings and the 6 of the adaptive
// Gaussian budget) opens, with a note; the settings it keeps read as written.
TEST(ConfigMigration, RunFolderOfAnOlderVersionOpens) {
  const fs::path run = test::scratch_dir("config_migration_run");
  fs::copy_file(old_config("46a5b55"), run_config_path(run));
  const TrainConfig c = read_run_config(run);
  EXPECT_EQ(c.mode, TrainMode::Intrinsic);
  EXPECT_EQ(c.iterations, 2000);
  EXPECT_EQ(c.input.data, "/data/steel_snowman");
  EXPECT_EQ(c.intrinsic.emit, EmitSource::Region);  // that version's default, written in the file
  EXPECT_EQ(c.intrinsic.detect_settled, 4000);
  nlohmann::json j = nlohmann::json::parse(read_text_file(old_config("46a5b55")));
  const ConfigMigrationResult m = migrate_config_json(j);
  EXPECT_EQ(m.from_version, 1);
  EXPECT_EQ(m.notes.size(), 10u);  // one per removed key, one for the colour rate's power added since
  EXPECT_FALSE(j.contains("intrinsic_prune_mirror_world_plane"));
  EXPECT_EQ(j.at("config_version"), kConfigVersion);
  // Trained with a removed setting on: refused by name.
  j = nlohmann::json::parse(read_text_file(old_config("46a5b55")));
  j["intrinsic_prune_mirror_world_plane"] = true;
  TrainConfig back;
  test::expect_error([&] { from_json(j, back); }, "'intrinsic_prune_mirror_world_plane' = true");
  // Written by this version, the same key is simply unknown.
  j = TrainConfig{};
  j["intrinsic_prune_mirror_world_plane"] = false;
  test::expect_error([&] { from_json(j, back); }, "unknown key 'intrinsic_prune_mirror_world_plane'");
}

// A run folder written at b4b5c26, before the emission, environment-sphere, mirror-world and warm-up settings
// existed: their absence reads as the behaviour it was trained with, not today's defaults.
TEST(ConfigMigration, KeysAnOlderFileLacksReadAsItsBehaviour) {
  TrainConfig c;
  from_json(nlohmann::json::parse(read_text_file(old_config("b4b5c26"))), c);
  EXPECT_EQ(c.intrinsic.emit, EmitSource::Region);
  EXPECT_EQ(c.intrinsic.env_distance, 0.0f);
  EXPECT_EQ(c.intrinsic.prune_mirror_world, 0.0f);
  EXPECT_FALSE(c.intrinsic.prune_mirror_world_repeat);
  EXPECT_EQ(c.intrinsic.warmup_min_fraction, 0.0f);
  EXPECT_EQ(c.intrinsic.detect_settled, 0);
  EXPECT_EQ(c.intrinsic.detect_depth_window, 0);
  EXPECT_EQ(c.lr.sh_dc_short_run_power, 0.0f);  // version 3
  EXPECT_NO_THROW(c.validate("old"));
  // Keys it lacks whose default was the behaviour before them keep the default.
  EXPECT_EQ(c.intrinsic.init_roughness, TrainConfig{}.intrinsic.init_roughness);
  EXPECT_TRUE(c.intrinsic.material_losses_in_warmup);
}

// The table's other kind: a renamed key, its value converted.
TEST(ConfigMigration, RenamedKeyWithConversion) {
  const std::vector<ConfigMigration> table = {
      {ConfigMigration::Kind::Renamed, 2, "sh_interval_k", "sh_degree_interval", nullptr, "counted in thousands",
       [](const nlohmann::json& v) { return nlohmann::json(v.get<int>() * 1000); }}};
  nlohmann::json j = {{"sh_interval_k", 2}};
  const ConfigMigrationResult m = migrate_config_json(j, table);
  EXPECT_EQ(j.at("sh_degree_interval"), 2000);
  EXPECT_FALSE(j.contains("sh_interval_k"));
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("'sh_interval_k' is now 'sh_degree_interval' (2 -> 2000)"), std::string::npos) << m.notes[0];
  nlohmann::json current = {{"config_version", 2}, {"sh_interval_k", 2}};
  EXPECT_TRUE(migrate_config_json(current, table).notes.empty());  // this version's files are left alone
}

// The user-facing settings: each documented once, under a section, and few enough to read.
TEST(ConfigReference, UserFacingSettingsAreDocumented) {
  size_t user = 0;
  std::set<std::string> keys;
  for (const ConfigKeyInfo& k : config_keys()) {
    EXPECT_TRUE(keys.insert(k.key).second) << k.key;
    EXPECT_FALSE(k.type.empty()) << k.key;
    EXPECT_EQ(k.section.empty(), k.doc.empty()) << k.key;
    user += !k.doc.empty();
  }
  EXPECT_GE(user, 20u);
  EXPECT_LE(user, 45u);
  const std::string page = train_options_reference();
  EXPECT_NE(page.find("| `iterations` | `30000` | whole number |"), std::string::npos);
  EXPECT_NE(page.find("| `densify_grad_threshold` | `0.0002` | number |"), std::string::npos);
}

}  // namespace
}  // namespace goris
