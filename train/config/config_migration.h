#pragma once
// Versions of a run's config.json and the table that brings an older one up to this build's, so that run
// folders and checkpoints written before a setting was renamed or removed still open (render, eval, resume,
// the editor). config.json records "config_version"; a file without it is version 1 (every file written
// before the field existed).
//
// Each entry of the table (config_migration.cpp) says what changed in the version `until` and how a file of
// an older version is read:
//  - renamed: the old key's value moves to the new key, converted where the meaning of a value changed;
//  - dropped: the key goes; the setting is gone from this build, so a file that used it at a value other
//    than the one it was off at is refused (the run needs the build that trained it);
//  - added:   a key older files lack because it came later, at a default that differs from what those runs
//    trained with: its absence reads as the value that reproduces them.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace goris {

// The config_version this build writes.
constexpr int kConfigVersion = 3;

struct ConfigMigration {
  enum class Kind { Renamed, Dropped, Added };
  Kind kind;
  int until;            // applies to files of an older version than this
  std::string key;      // the key as older files have it (renamed, dropped) or lack it (added)
  std::string new_key;  // renamed: its name now
  // dropped: the value it was off at (null: it acted only through another setting, any value loads);
  // added: the value a file without the key means.
  nlohmann::json value;
  std::string reason;   // why, for the note and the error (one clause)
  // renamed: the old value as the new key takes it (null function: unchanged); throws goris::Error for a
  // value it cannot convert.
  nlohmann::json (*convert)(const nlohmann::json&) = nullptr;
};

// This build's table, oldest first.
const std::vector<ConfigMigration>& config_migrations();

struct ConfigMigrationResult {
  int from_version = kConfigVersion;  // the file's config_version
  std::vector<std::string> notes;     // one per change: "'KEY' ...: REASON"
};

// Brings `j` (a config.json object) to kConfigVersion in place with `table` and says what changed. Throws
// goris::Error for a version newer than this build's or not a whole number, and for a dropped setting the
// file used. A file of this version only gains nothing; one without config_version gains it.
ConfigMigrationResult migrate_config_json(nlohmann::json& j,
                                          const std::vector<ConfigMigration>& table = config_migrations());

// The dropped entry of `key` in this build's table, or nullptr (for `--set` of a removed key).
const ConfigMigration* dropped_config_key(const std::string& key);

// Prints the notes of a migration of SOURCE to stderr, once per process for the same notes: a command reads
// a run's config.json and then its checkpoint, which carries the same configuration.
void print_config_migration_notes(const std::string& source, const ConfigMigrationResult& migration);

}  // namespace goris
