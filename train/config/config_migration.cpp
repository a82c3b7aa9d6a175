#include "train/config/config_migration.h"

#include <cmath>
#include <cstdio>
#include <mutex>
#include <set>

#include "core/util/error.h"

namespace goris {

namespace {

using Kind = ConfigMigration::Kind;
using nlohmann::json;

ConfigMigration dropped(const char* key, json off, const char* reason) {
  return {Kind::Dropped, 2, key, "", std::move(off), reason};
}
ConfigMigration added(const char* key, json absent, const char* reason, int until = 2) {
  return {Kind::Added, until, key, "", std::move(absent), reason};
}

const char* kMeasured = "it measured no better than without (docs/design/deviations.md, Removed settings)";
const char* kOffWhenAdded = "it came in off, and the run predates it";

}  // namespace

const std::vector<ConfigMigration>& config_migrations() {
  static const std::vector<ConfigMigration> kTable = {
      // Version 2: config.json records config_version. Settings removed before that (version-1 files may
      // hold them) ...
      dropped("intrinsic_net_residual", false, kMeasured),
      dropped("intrinsic_ray_offset_normal", false, kMeasured),
      dropped("intrinsic_region_rough", 0.0, kMeasured),
      dropped("intrinsic_roughness_rough", 0.0, kMeasured),
      dropped("intrinsic_roughness_follows_region", 0.0, kMeasured),
      dropped("intrinsic_prune_mirror_world_plane", false,
              "it cost stage 1 4-6 dB on steel_snowman (docs/design/deviations.md, Removed settings)"),
      dropped("densify_stop", "fixed", kMeasured),
      dropped("densify_holdout_every", nullptr, "it acted only through densify_stop=adaptive, removed"),
      dropped("densify_stop_check_interval", nullptr, "it acted only through densify_stop=adaptive, removed"),
      dropped("densify_stop_window", nullptr, "it acted only through densify_stop=adaptive, removed"),
      dropped("densify_stop_min_gain", nullptr, "it acted only through densify_stop=adaptive, removed"),
      dropped("densify_stop_min_steps", nullptr, "it acted only through densify_stop=adaptive, removed"),
      // ... and settings added with the behaviour before them, whose default changed later: a version-1
      // file without one was trained with that behaviour.
      added("intrinsic_emit", "region", "the paper's emission, from before the setting"),
      added("intrinsic_env_distance", 0.0, "the environment at infinity, from before the setting"),
      added("intrinsic_prune_mirror_world", 0.0, kOffWhenAdded),
      added("intrinsic_prune_mirror_world_repeat", false, kOffWhenAdded),
      added("intrinsic_warmup_min_fraction", 0.0, "the warm-up scaled with the run, from before the setting"),
      added("intrinsic_detect_settled", 0, "detection without the wait for settled geometry, from before the setting"),
      added("intrinsic_detect_depth_window", 0, "detection at each pixel's own depth, from before the setting"),
      // Version 3: the SH colour's rate raised in runs shorter than the full schedule.
      added("lr_sh_dc_short_run_power", 0.0, "the colour's fixed rate, from before the setting", 3),
  };
  return kTable;
}

const ConfigMigration* dropped_config_key(const std::string& key) {
  for (const ConfigMigration& m : config_migrations())
    if (m.kind == Kind::Dropped && m.key == key) return &m;
  return nullptr;
}

ConfigMigrationResult migrate_config_json(json& j, const std::vector<ConfigMigration>& table) {
  if (!j.is_object()) throw Error("training configuration: expected a JSON object");
  int version = 1;
  if (j.contains("config_version")) {
    const json& v = j["config_version"];
    if (!v.is_number_integer() || v.get<long long>() < 1)
      throw Error("training configuration: 'config_version' must be a whole number >= 1, got " + v.dump());
    if (v.get<long long>() > kConfigVersion)
      throw Error("training configuration: config_version " + v.dump() + " is newer than this build reads (" +
                  std::to_string(kConfigVersion) + "): the run needs a newer build of goris");
    version = v.get<int>();
  }
  ConfigMigrationResult result;
  result.from_version = version;
  std::vector<std::string>& notes = result.notes;
  for (const ConfigMigration& m : table) {
    if (version >= m.until) continue;
    switch (m.kind) {
      case Kind::Renamed: {
        if (!j.contains(m.key)) break;
        json v = j[m.key];
        if (m.convert) {
          try {
            v = m.convert(v);
          } catch (const std::exception& e) {
            throw Error("training configuration: '" + m.key + "' = " + j[m.key].dump() + " (now '" + m.new_key +
                        "'): " + e.what());
          }
        }
        notes.push_back("'" + m.key + "' is now '" + m.new_key + "'" +
                        (v != j[m.key] ? " (" + j[m.key].dump() + " -> " + v.dump() + ")" : std::string()) + ": " +
                        m.reason);
        j.erase(m.key);
        j[m.new_key] = std::move(v);
        break;
      }
      case Kind::Dropped: {
        if (!j.contains(m.key)) break;
        const json& v = j[m.key];
        // Numbers compare by value (0 and 0.0 alike).
        const bool off = m.value.is_null() || v == m.value ||
                         (v.is_number() && m.value.is_number() && v.get<double>() == m.value.get<double>());
        if (!off)
          throw Error("training configuration: '" + m.key + "' = " + v.dump() +
                      " is a setting this version no longer has (" + m.reason + "; it was off at " +
                      m.value.dump() + "): the run needs the version that trained it");
        notes.push_back("'" + m.key + "' dropped: " + m.reason);
        j.erase(m.key);
        break;
      }
      case Kind::Added:
        if (j.contains(m.key)) break;
        j[m.key] = m.value;
        notes.push_back("'" + m.key + "' absent, read as " + m.value.dump() + ": " + m.reason);
        break;
    }
  }
  j["config_version"] = kConfigVersion;
  return result;
}

void print_config_migration_notes(const std::string& source, const ConfigMigrationResult& migration) {
  if (migration.notes.empty()) return;
  static std::mutex mutex;
  static std::set<std::string> printed;
  const std::lock_guard<std::mutex> lock(mutex);
  std::string changes;
  for (const std::string& n : migration.notes) changes += "\n  " + n;
  if (!printed.insert(changes).second) return;  // the same changes again: the run's checkpoint after its config
  std::fprintf(stderr, "note: %s was written by an older version (config_version %d) and is read as version %d:%s\n",
               source.c_str(), migration.from_version, kConfigVersion, changes.c_str());
}

}  // namespace goris
