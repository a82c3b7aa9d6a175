// `goris`: the command-line twin of the editor. Wiring only: every subcommand is a cmd_*.cpp file that
// registers itself (app/cli_common/command.h): the user commands here, the `goris bench` commands in app/bench.
#include <cstdio>
#include <exception>

#include "app/cli_common/command.h"
#include "core/util/error.h"

int main(int argc, char** argv) {
  using namespace goris::cli;
  CLI::App app{"GOR-IS Studio: remove objects and their reflections from 3D Gaussian scenes", "goris"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "goris 0.1.0");
  add_registered_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const goris::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return exit_code();
}
