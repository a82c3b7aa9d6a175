#pragma once
// What a stage's stored output was made from: a JSON object of its inputs' fingerprints and its options,
// kept beside the output (e.g. RUN/removal/made_from.json). A rerun compares the record with what it
// would make the output from now: reuse or resume only when nothing changed, otherwise start the stage
// over, saying which inputs changed.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace goris {

// "" when the record at `path` equals `now`; otherwise what differs, e.g. "selection, options.inpainter"
// (keys of nested objects joined by dots), or "no record of what it was made from" when the file is
// missing or not JSON.
std::string made_from_changes(const std::filesystem::path& path, const nlohmann::json& now);

// Writes the record through a temporary file.
void write_made_from(const std::filesystem::path& path, const nlohmann::json& now);

// The keys whose values differ between two JSON objects (nested objects compared key by key).
std::string json_differences(const nlohmann::json& before, const nlohmann::json& now);

}  // namespace goris
