#include "app/cli_common/command.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/compute/device_choice.h"

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
void add_registered_commands(CLI::App& root) {
  auto& cmds = registry();
  std::stable_sort(cmds.begin(), cmds.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& [order, setup] : cmds) setup(root);
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

CLI::Option* add_device_option(CLI::App& command, std::string& device, const std::string& use) {
  std::string help;
  for (const std::string& name : enum_name_list<DeviceChoice>()) help += (help.empty() ? "" : " | ") + name;
  if (!use.empty()) help += " (" + use + ")";
  return command.add_option("--device", device, help)->check(CLI::IsMember(enum_name_list<DeviceChoice>()));
}

void set_exit_code(int code) { g_exit_code = code; }
int exit_code() { return g_exit_code; }

}  // namespace goris::cli
