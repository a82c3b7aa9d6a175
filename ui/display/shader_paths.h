#pragma once
// Where the display shaders (shaders/*.glsl) are found at run time, so they can be edited without a
// rebuild: $GORIS_SHADER_DIR, else the source tree's shaders/ (compiled in), else shaders/ next to the
// executable (the build copies them there), else ../share/goris-studio/shaders from the executable.
#include <filesystem>
#include <vector>

namespace goris::ui {

// The candidates in the order above (for error messages and tests).
std::vector<std::filesystem::path> shader_dir_candidates();
// The first candidate holding `probe` (a file name); throws goris::Error listing the places tried.
std::filesystem::path find_shader_dir(const char* probe = "channel.frag.glsl");

}  // namespace goris::ui
