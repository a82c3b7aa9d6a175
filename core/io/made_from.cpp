#include "core/io/made_from.h"

#include <set>
#include <system_error>

#include "core/io/file_bytes.h"
#include "core/io/json_file.h"

namespace goris {

namespace {
void collect_differences(const nlohmann::json& a, const nlohmann::json& b, const std::string& prefix, std::string& out) {
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (auto it = a.begin(); it != a.end(); ++it) keys.insert(it.key());
    for (auto it = b.begin(); it != b.end(); ++it) keys.insert(it.key());
    for (const std::string& k : keys) {
      const std::string name = prefix.empty() ? k : prefix + "." + k;
      const nlohmann::json none;
      collect_differences(a.contains(k) ? a[k] : none, b.contains(k) ? b[k] : none, name, out);
    }
    return;
  }
  if (a != b) out += (out.empty() ? "" : ", ") + (prefix.empty() ? std::string("everything") : prefix);
}
}  // namespace

std::string json_differences(const nlohmann::json& before, const nlohmann::json& now) {
  std::string out;
  collect_differences(before, now, "", out);
  return out;
}

std::string made_from_changes(const std::filesystem::path& path, const nlohmann::json& now) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return "no record of what it was made from";
  const nlohmann::json before = nlohmann::json::parse(read_text_file(path), nullptr, false);
  if (before.is_discarded()) return "no record of what it was made from";
  return json_differences(before, now);
}

void write_made_from(const std::filesystem::path& path, const nlohmann::json& now) { write_json_file(path, now); }

}  // namespace goris
