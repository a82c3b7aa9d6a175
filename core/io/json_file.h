#pragma once
// A JSON document written as indented text (with a final newline) through a temporary file renamed into
// place - the one way run folders, reports and selections are written.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"

namespace goris {

inline void write_json_file(const std::filesystem::path& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  write_file_bytes(path, text.data(), text.size());
}

}  // namespace goris
