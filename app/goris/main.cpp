// `goris`: the command-line twin of the editor. Wiring only: every subcommand is a cmd_*.cpp file.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

#include "app/goris/command.h"
#include "core/util/error.h"

namespace goris::cli {
namespace {
std::vector<std::pair<int, CommandSetup>>& registry() {
  static std::vector<std::pair<int, CommandSetup>> r;
  return r;
}
int g_exit_code = 0;
}  // namespace

bool register_command(int order, CommandSetup setup) {
  registry().emplace_back(order, setup);
  return true;
}
CLI::App& subcommand_group(CLI::App& parent, const std::string& name, const std::string& description) {
  for (CLI::App* c : parent.get_subcommands([](CLI::App*) { return true; }))
    if (c->get_name() == name) return *c;
  CLI::App* c = parent.add_subcommand(name, description);
  c->require_subcommand(1);
  return *c;
}

CLI::Option* add_data_option(CLI::App& command, std::string& data) {
  return command.add_option("--data", data,
                            "The run's data set at its new folder, when it moved after training: replaces "
                            "config.json's \"data\" for this command (checked to hold the same training views)");
}

void set_exit_code(int code) { g_exit_code = code; }
int exit_code() { return g_exit_code; }

}  // namespace goris::cli

int main(int argc, char** argv) {
  using namespace goris::cli;
  CLI::App app{"GOR-IS Studio: remove objects and their reflections from 3D Gaussian scenes", "goris"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "goris 0.1.0");
  auto& cmds = registry();
  std::stable_sort(cmds.begin(), cmds.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& [order, setup] : cmds) setup(app);
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
