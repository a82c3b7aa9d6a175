// gui_screenshot_check PNG [--expect N]: checks an editor screenshot against the PNG's .layout.json
// (written by goris-studio's `screenshot`): there are N viewports (when given), every viewport's image
// is non-blank (its pixels vary and are not all black) and no two viewports look alike. Prints one line per
// viewport; exits 1 with the reason on failure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/io/image.h"
#include "tests/gui/layout_file.h"

namespace {

struct Tile {
  std::string name, channel;
  std::vector<float> grey;  // kSamples x kSamples samples of the image (mean of RGB)
  double mean = 0, stddev = 0;
};

constexpr int kSamples = 48;
constexpr float kChooserHeight = 30;  // the channel chooser covers the top of a viewport: left out

int fail(const std::string& why) {
  std::fprintf(stderr, "FAILED: %s\n", why.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return fail("usage: gui_screenshot_check PNG [--expect N]");
  const std::filesystem::path png = argv[1];
  int expect = -1;
  for (int i = 2; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--expect") expect = std::atoi(argv[i + 1]);
  nlohmann::json layout;
  goris::Image img;
  try {
    layout = goris::test::read_layout(png);
    img = goris::read_image(png);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  if (img.width != layout.value("width", 0) || img.height != layout.value("height", 0))
    return fail("the screenshot's size differs from the layout's");
  const int ch = img.channels;

  std::vector<Tile> tiles;
  for (const auto& v : layout.at("viewports")) {
    Tile t;
    t.name = v.at("name").get<std::string>();
    t.channel = v.at("channel").get<std::string>();
    const float x = v.at("x").get<float>() + 2, w = v.at("w").get<float>() - 4;
    const float y = v.at("y").get<float>() + kChooserHeight, h = v.at("h").get<float>() - kChooserHeight - 2;
    if (w < 16 || h < 16) return fail(t.name + ": no image (" + std::to_string(w) + "x" + std::to_string(h) + ")");
    double sum = 0, sum2 = 0;
    for (int j = 0; j < kSamples; ++j)
      for (int i = 0; i < kSamples; ++i) {
        const int px = std::clamp(int(x + (float(i) + 0.5f) * w / kSamples), 0, img.width - 1);
        const int py = std::clamp(int(y + (float(j) + 0.5f) * h / kSamples), 0, img.height - 1);
        float g = 0;
        for (int c = 0; c < std::min(ch, 3); ++c) g += img.pixels[(size_t(py) * img.width + px) * ch + c];
        g /= float(std::min(ch, 3));
        t.grey.push_back(g);
        sum += g;
        sum2 += double(g) * g;
      }
    const double n = double(t.grey.size());
    t.mean = sum / n;
    t.stddev = std::sqrt(std::max(0.0, sum2 / n - t.mean * t.mean));
    std::printf("%-6s %-10s mean %.3f  stddev %.3f\n", t.name.c_str(), t.channel.c_str(), t.mean, t.stddev);
    tiles.push_back(std::move(t));
  }
  if (expect >= 0 && int(tiles.size()) != expect)
    return fail("expected " + std::to_string(expect) + " viewports, the layout has " + std::to_string(tiles.size()));
  for (const Tile& t : tiles)
    if (t.stddev < 0.02 || t.mean < 0.01) return fail(t.name + " (" + t.channel + ") is blank");
  for (size_t a = 0; a < tiles.size(); ++a)
    for (size_t b = a + 1; b < tiles.size(); ++b) {
      double d = 0;
      for (size_t k = 0; k < tiles[a].grey.size(); ++k) d += std::abs(tiles[a].grey[k] - tiles[b].grey[k]);
      d /= double(tiles[a].grey.size());
      if (d < 0.02)
        return fail(tiles[a].name + " (" + tiles[a].channel + ") and " + tiles[b].name + " (" + tiles[b].channel +
                    ") look the same (mean difference " + std::to_string(d) + ")");
    }
  std::printf("%zu viewports: all non-blank and different\n", tiles.size());
  return 0;
}
