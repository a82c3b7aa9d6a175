#include "ui/display/shader_paths.h"

#include "core/util/error.h"
#include "core/util/resource_paths.h"

namespace goris::ui {

namespace fs = std::filesystem;

std::vector<fs::path> shader_dir_candidates() {
#ifdef GORIS_SHADER_DIR
  return resource_dir_candidates("GORIS_SHADER_DIR", GORIS_SHADER_DIR, "shaders");
#else
  return resource_dir_candidates("GORIS_SHADER_DIR", nullptr, "shaders");
#endif
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
