// The training configuration's files: config.json of older versions (core/train/config_migration.h).
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/train/config_migration.h"
#include "core/train/run_folder.h"
#include "core/train/train_config.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

namespace fs = std::filesystem;

// config.json files written by older commits (tests/fixtures/config/config_<commit>.json: their to_json of
// the default configuration, with data, mode and iterations set).
fs::path old_config(const char* commit) {
  return test::resource_dir().parent_path() / "tests" / "fixtures" / "config" / ("config_" + std::string(commit) + ".json");
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
}

// A run folder written at 46a5b55 (with 9 keys removed since: 3 stage-1 settings and the 6 of the adaptive
// Gaussian budget) opens, with a note; the settings it keeps read as written.
TEST(ConfigMigration, RunFolderOfAnOlderVersionOpens) {
  const fs::path run = test::scratch_dir("config_migration_run");
  fs::copy_file(old_config("46a5b55"), run_config_path(run));
  const TrainConfig c = read_run_config(run);
  EXPECT_EQ(c.mode, "intrinsic");
  EXPECT_EQ(c.iterations, 2000);
  EXPECT_EQ(c.data, "/data/steel_snowman");
  EXPECT_EQ(c.intrinsic.emit, "region");  // that version's default, written in the file
  EXPECT_EQ(c.intrinsic.detect_settled, 4000);
  nlohmann::json j = nlohmann::json::parse(read_text_file(old_config("46a5b55")));
  const ConfigMigrationResult m = migrate_config_json(j);
  EXPECT_EQ(m.from_version, 1);
  EXPECT_EQ(m.notes.size(), 9u);  // one per removed key
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
  EXPECT_EQ(c.intrinsic.emit, "region");
  EXPECT_EQ(c.intrinsic.env_distance, 0.0f);
  EXPECT_EQ(c.intrinsic.prune_mirror_world, 0.0f);
  EXPECT_FALSE(c.intrinsic.prune_mirror_world_repeat);
  EXPECT_EQ(c.intrinsic.warmup_min_fraction, 0.0f);
  EXPECT_EQ(c.intrinsic.detect_settled, 0);
  EXPECT_EQ(c.intrinsic.detect_depth_window, 0);
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

}  // namespace
}  // namespace goris
