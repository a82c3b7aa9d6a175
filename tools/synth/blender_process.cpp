#include "tools/synth/blender_process.h"

#include <unistd.h>

#include "core/util/error.h"

namespace goris::synth {
namespace fs = std::filesystem;

fs::path find_blender(const fs::path& requested) {
  const std::string install = "install it with `sudo apt-get install blender` (Blender 3.4 or newer)";
  if (!requested.empty()) {
    if (!fs::is_regular_file(requested) || ::access(requested.c_str(), X_OK) != 0)
      throw Error(requested.string(), "no Blender executable here; " + install + " or pass --blender PATH");
    return requested;
  }
  if (auto found = find_on_path("blender")) return *found;
  throw Error("blender", "not found on PATH; " + install + " or pass --blender PATH");
}

}  // namespace goris::synth
