// gui_export_check: checks of the GUI export test (tests/gui/studio_export.cmake) on what the editor wrote.
//
//   gui_export_check ply RUN FILE intrinsic|baked
//       FILE reads back (core/io/ply.h) with as many Gaussians as RUN's model; an intrinsic PLY carries the
//       intrinsic attributes as extra properties, a baked one none, SH degree 3, and its OUT.json beside it.
//   gui_export_check renders DIR N
//       DIR holds N frames named in cameras.json, each a PNG of the size cameras.json gives, and
//       contact_sheet.png.
//   gui_export_check dialog WITH.png WITHOUT.png
//       the two screenshots differ over most of the window's central box, where the dialog opens.
// Prints what it found; exits 1 with the reason on failure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/io/image.h"
#include "core/io/ply.h"
#include "core/util/error.h"
#include "train/run/run_folder.h"

namespace {

namespace fs = std::filesystem;

int fail(const std::string& why) {
  std::fflush(stdout);
  std::fprintf(stderr, "FAILED: %s\n", why.c_str());
  return 1;
}

int check_ply(const fs::path& run, const fs::path& file, const std::string& kind) {
  const goris::GaussianModel model = goris::load_run_model(run, goris::Device::CPU);
  const goris::GaussianPly ply = goris::read_ply(file);
  std::printf("%s: %zu Gaussians, SH degree %d, %zu extra properties\n", file.string().c_str(), ply.count,
              ply.sh_degree, ply.extras.size());
  if (ply.count != model.count())
    return fail(file.string() + " has " + std::to_string(ply.count) + " Gaussians, the run's model " +
                std::to_string(model.count()));
  if (kind == "intrinsic") {
    for (const char* name : {"diffuse_0", "fresnel_0", "roughness", "region", "label"})
      if (!ply.extra(name)) return fail(file.string() + " lacks the intrinsic property " + name);
  } else {
    if (!ply.extras.empty()) return fail(file.string() + ": a baked PLY should have no extra properties");
    if (ply.sh_degree != 3) return fail(file.string() + ": a baked PLY should have SH degree 3");
    fs::path json = file;
    json.replace_extension(".json");
    if (!fs::exists(json)) return fail(json.string() + " (the baked PLY's report) is missing");
  }
  return 0;
}

int check_renders(const fs::path& dir, int frames) {
  std::ifstream in(dir / "cameras.json");
  if (!in) return fail((dir / "cameras.json").string() + " is missing");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("cameras")) return fail((dir / "cameras.json").string() + " is malformed");
  const auto& cams = j["cameras"];
  if (int(cams.size()) != frames)
    return fail("cameras.json lists " + std::to_string(cams.size()) + " frames, expected " + std::to_string(frames));
  for (const auto& c : cams) {
    const fs::path png = dir / (c["name"].get<std::string>() + ".png");
    const goris::Image im = goris::read_image(png);
    if (im.width != c["width"].get<int>() || im.height != c["height"].get<int>())
      return fail(png.string() + " is " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                  ", cameras.json says " + c["width"].dump() + "x" + c["height"].dump());
    std::printf("%s: %dx%d\n", png.filename().string().c_str(), im.width, im.height);
  }
  const goris::Image sheet = goris::read_image(dir / "contact_sheet.png");
  std::printf("contact_sheet.png: %dx%d\n", sheet.width, sheet.height);
  return 0;
}

int check_dialog(const fs::path& with, const fs::path& without) {
  const goris::Image a = goris::read_image(with), b = goris::read_image(without);
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    return fail("the two screenshots differ in size");
  const std::vector<float> pa = a.pixels.to_host(), pb = b.pixels.to_host();
  // The dialog opens centred at (50 %, 42 %) of the window: look at a box well inside it.
  const int x0 = a.width * 42 / 100, x1 = a.width * 58 / 100, y0 = a.height * 36 / 100, y1 = a.height * 48 / 100;
  long differ = 0, total = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      float d = 0;
      for (int c = 0; c < a.channels; ++c) {
        const size_t i = (size_t(y) * size_t(a.width) + size_t(x)) * size_t(a.channels) + size_t(c);  // HWC
        d = std::max(d, std::abs(pa[i] - pb[i]));
      }
      differ += d > 2.0f / 255.0f;
      ++total;
    }
  const double share = double(differ) / double(total);
  std::printf("dialog box: %.0f %% of %ld pixels differ\n", 100.0 * share, total);
  if (share < 0.5) return fail("the Export dialog does not show in " + with.string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string cmd = argc > 1 ? argv[1] : "";
    if (cmd == "ply" && argc == 5) return check_ply(argv[2], argv[3], argv[4]);
    if (cmd == "renders" && argc == 4) return check_renders(argv[2], std::stoi(argv[3]));
    if (cmd == "dialog" && argc == 4) return check_dialog(argv[2], argv[3]);
    return fail("usage: gui_export_check ply RUN FILE intrinsic|baked | renders DIR N | dialog WITH.png WITHOUT.png");
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}
