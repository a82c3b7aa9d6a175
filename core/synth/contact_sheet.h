#pragma once
#include <filesystem>

namespace goris::synth {

// contact_sheet.png of a rendered scene folder: one row per test view, columns full_ | r_ | mask
// (transparent background shown grey; small renders are enlarged to at least 128 pixels).
void write_contact_sheet(const std::filesystem::path& scene_dir, const std::filesystem::path& png_path);

}  // namespace goris::synth
