#pragma once
// A number from the JSON a child `goris` command wrote (metrics.json, result.json): NaN where the key is
// absent, null or not a number, e.g. a mean over non-finite renders.
#include <cmath>

#include <nlohmann/json.hpp>

namespace goris::cli {

// j[key] when it is a number, else NaN.
inline double json_number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

}  // namespace goris::cli
