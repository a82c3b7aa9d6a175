#pragma once
#include <filesystem>

namespace goris::synth {

// contact_sheet.png of a rendered scene folder: a grid of up to 8 test views spread over the test set, each a
// captioned triplet full_ | r_ | mask (transparent background shown grey; small renders are enlarged to at
// least 256 pixels), so a person sees the target's reflection in full_ and gone in r_.
void write_contact_sheet(const std::filesystem::path& scene_dir, const std::filesystem::path& png_path);

}  // namespace goris::synth
