#pragma once
// Each `goris` subcommand lives in its own cmd_*.cpp (the user commands in app/goris, the benchmarks in
// app/bench) and registers itself here, so adding a command never touches main.cpp. A command's setup adds
// a CLI11 subcommand to the root app and sets its callback; the callback throws goris::Error for bad input
// (main prints it and exits 1) and returns normally on success.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/util/named_enum.h"

namespace goris::cli {

using CommandSetup = void (*)(CLI::App& root);

// `order` sorts the subcommands in --help.
bool register_command(int order, CommandSetup setup);
// Adds every registered command to `root`, in their order (main calls it once, before parsing).
void add_registered_commands(CLI::App& root);

// The subcommand `name` of `parent`, created on first use: lets several files add children to one group
// (e.g. each `goris bench KIND` lives in its own file and registers with an order after the group's).
CLI::App& subcommand_group(CLI::App& parent, const std::string& name, const std::string& description);

// --data DIR of the commands that read a run's data set (render, eval, select, remove, export): the data
// set's new folder when it moved after training, in place of config.json's "data" for this one command
// (train/run/run_data.h checks that it holds the same training views).
CLI::Option* add_data_option(CLI::App& command, std::string& data);

// The names of a named enumeration (core/util/named_enum.h), for an option's IsMember check.
template <class E>
std::vector<std::string> enum_name_list() {
  std::vector<std::string> names;
  for (const auto& [value, name] : EnumNames<E>::names) names.emplace_back(name);
  return names;
}

// --device of the commands that compute: auto, cpu or cuda (DeviceChoice, core/compute/device_choice.h);
// `use` says what runs there when it is not the whole command.
CLI::Option* add_device_option(CLI::App& command, std::string& device, const std::string& use = "");

// Exit code a callback may set for "finished, but with a non-fatal failure" (e.g. a failed check).
void set_exit_code(int code);
int exit_code();

}  // namespace goris::cli

#define GORIS_COMMAND(order, fn) \
  static const bool goris_registered_##fn = ::goris::cli::register_command(order, fn)
