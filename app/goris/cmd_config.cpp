// `goris config`: the training settings and presets. With no option, the user-facing settings by section
// with their defaults; --all lists every config.json key; --reference prints docs/reference/train-options.md
// (the page is generated from the documentation beside each setting in train/config/train_config.cpp);
// --presets lists the presets with their files, descriptions and settings.
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli_common/command.h"
#include "core/util/error.h"
#include "train/config/config_presets.h"
#include "train/config/train_config.h"

namespace {
using namespace goris;

struct Options {
  bool all = false, reference = false, presets = false;
};

void list_settings(bool all) {
  std::string section = "\n";
  for (const ConfigKeyInfo& k : config_keys()) {
    if (all) {
      std::printf("%-40s %-14s %s%s\n", k.key.c_str(), k.default_value.c_str(), k.type.c_str(),
                  k.doc.empty() ? "" : " (user-facing)");
      continue;
    }
    if (k.doc.empty()) continue;
    if (k.section != section) std::printf("%s%s:\n", section == "\n" ? "" : "\n", k.section.c_str());
    section = k.section;
    std::printf("  %-32s %-10s %s\n", k.key.c_str(), k.default_value.c_str(), k.doc.c_str());
  }
  if (!all)
    std::printf("\nSet one with `goris train --set KEY=VALUE`; `goris config --all` lists every setting, "
                "docs/reference/train-options.md documents these.\n");
}

void list_presets() {
  const std::vector<std::string> names = config_preset_names();
  if (names.empty()) throw Error(find_preset_dir().string(), "holds no presets (NAME.json files)");
  for (const std::string& n : names) {
    const ConfigPreset p = load_config_preset(n);
    std::printf("%s (%s)\n  %s\n", p.name.c_str(), p.file.c_str(), p.description.c_str());
    for (const std::string& kv : p.settings) std::printf("    %s\n", kv.c_str());
  }
}

void setup_config(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("config", "The training settings (config.json keys) and presets");
  auto* all = c->add_flag("--all", o->all, "Every config.json key with its default and type");
  auto* ref = c->add_flag("--reference", o->reference,
                          "The Markdown page docs/reference/train-options.md (the user-facing settings)");
  auto* pre = c->add_flag("--presets", o->presets, "The presets: file, description and settings");
  all->excludes(ref)->excludes(pre);
  ref->excludes(pre);
  c->callback([o] {
    if (o->reference)
      std::fputs(train_options_reference().c_str(), stdout);
    else if (o->presets)
      list_presets();
    else
      list_settings(o->all);
  });
}

}  // namespace
GORIS_COMMAND(22, setup_config);
