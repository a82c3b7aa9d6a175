#pragma once
// Where a folder of run-time resources (the editor's shaders, the training presets) is found, in this
// order: $ENV_VAR; the source tree's folder (compiled in, so that an edit needs no rebuild); NAME/ next to
// the executable (the build copies it there); ../share/goris-studio/NAME from the executable (an installed
// layout).
#include <filesystem>
#include <string>
#include <vector>

namespace goris {

// The candidates in that order; `source_dir` may be null (not compiled in).
std::vector<std::filesystem::path> resource_dir_candidates(const char* env_var, const char* source_dir,
                                                           const std::string& name);

}  // namespace goris
