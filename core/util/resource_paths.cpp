#include "core/util/resource_paths.h"

#include <cstdlib>
#include <system_error>

namespace goris {

namespace fs = std::filesystem;

std::vector<fs::path> resource_dir_candidates(const char* env_var, const char* source_dir, const std::string& name) {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv(env_var); env && *env) dirs.emplace_back(env);
  if (source_dir && *source_dir) dirs.emplace_back(source_dir);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(exe.parent_path() / name);
    dirs.push_back(exe.parent_path().parent_path() / "share" / "goris-studio" / name);
  }
  return dirs;
}

}  // namespace goris
