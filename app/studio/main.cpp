// `goris-studio [DATA|RUN] [--script FILE] [--width W --height H]`: the desktop editor. Argument parsing
// and wiring only; the editor lives in ui/ (ui/shell/studio_app.h).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "core/util/error.h"
#include "ui/shell/studio_app.h"

int main(int argc, char** argv) {
  CLI::App cli{"GOR-IS Studio: train, inspect, select and remove objects from Gaussian scenes"};
  goris::ui::StudioOptions o;
  std::string script;
  cli.add_option("path", o.open_path, "A data set folder or a run folder to open");
  cli.add_option("--script", script, "Run the UI actions of FILE, one per line (see ui/script/script.h)");
  cli.add_option("--width", o.width, "Window width in pixels")->check(CLI::Range(320, 16384));
  cli.add_option("--height", o.height, "Window height in pixels")->check(CLI::Range(240, 16384));
  cli.add_option("--max-fps", o.max_fps, "Frame rate cap of the GUI (default 60)")->check(CLI::Range(1.0, 1000.0));
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  }
  o.script = script;
  try {
    goris::ui::StudioApp app(o);
    return app.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
