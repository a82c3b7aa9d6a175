#include "ui/shader_paths.h"

#include <cstdlib>
#include <system_error>

#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;

std::vector<fs::path> shader_dir_candidates() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("GORIS_SHADER_DIR"); env && *env) dirs.emplace_back(env);
#ifdef GORIS_SHADER_DIR
  dirs.emplace_back(GORIS_SHADER_DIR);
#endif
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(exe.parent_path() / "shaders");
    dirs.push_back(exe.parent_path().parent_path() / "share" / "goris-studio" / "shaders");
  }
  return dirs;
}

fs::path find_shader_dir(const char* probe) {
  std::string tried;
  for (const fs::path& d : shader_dir_candidates()) {
    if (fs::exists(d / probe)) return d;
    tried += "\n  " + d.string();
  }
  throw Error(probe, "shader not found; looked in:" + tried + "\n(set GORIS_SHADER_DIR to the shaders/ folder)");
}

}  // namespace goris::ui
