#include "train/run/run_data.h"

#include <cstdio>
#include <string_view>

#include "core/util/error.h"
#include "core/util/fnv1a.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"

namespace goris {
namespace fs = std::filesystem;

std::string training_views_fingerprint(const Dataset& dataset) {
  Fnv1a h;
  auto add = [&h](std::string_view bytes) {
    h.bytes(bytes.data(), bytes.size());
    h.byte(0);  // a separator, so that "ab" + "c" differs from "a" + "bc"
  };
  for (const View& v : dataset.train) {
    add(v.name);
    add(std::to_string(v.source_width) + "x" + std::to_string(v.source_height));
  }
  return std::to_string(dataset.train.size()) + " views, " + h.hex();
}

void use_run_data(const fs::path& run_dir, TrainConfig& config, const std::string& data, const std::string& how) {
  std::error_code ec;
  const bool recorded_exists = !config.input.data.empty() && fs::exists(config.input.data, ec);
  const std::string config_json = run_config_path(run_dir).string();
  if (data.empty()) {
    if (recorded_exists) return;
    throw Error(config.input.data, "not found: this data set path comes from " + config_json +
                                 " (its \"data\" entry). If the data set moved, give its new folder as " + how +
                                 " (checked to hold the same training views), or edit \"data\" in config.json");
  }
  const fs::path given = fs::weakly_canonical(fs::absolute(data), ec);
  if (recorded_exists && fs::weakly_canonical(config.input.data, ec) == given) return;  // the run's own folder
  const Dataset ds = load_dataset(given, dataset_options(config));  // errors name the folder
  const std::string views = training_views_fingerprint(ds);
  const std::string not_this = "this run was trained on " + config.input.data + ", not " + given.string() + ": ";
  const std::string hint = ". If the data set moved, give its new folder as " + how;
  if (!config.input.data_views.empty() && views != config.input.data_views)
    throw Error(run_dir.string(), not_this + "the training views differ (" + views + " vs the run's " +
                                      config.input.data_views + "; names and image sizes)" + hint);
  if (config.input.data_views.empty() && recorded_exists)
    throw Error(run_dir.string(), not_this + "the run's data set is still there, and the run records no fingerprint "
                                             "of its views to check another folder against" + hint);
  if (config.input.data_views.empty())
    std::fprintf(stderr, "warning: %s records no fingerprint of its training views: %s is used unchecked as the data "
                         "set that was at %s\n",
                 config_json.c_str(), given.string().c_str(), config.input.data.c_str());
  else
    std::fprintf(stderr, "note: %s was trained on the data set at %s; using %s, which holds the same training views "
                         "(%s; names and image sizes)\n", run_dir.string().c_str(), config.input.data.c_str(),
                 given.string().c_str(), views.c_str());
  config.input.data = given.string();
}

TrainConfig read_run_config_with_data(const fs::path& run_dir, const std::string& data) {
  TrainConfig config = read_run_config(run_dir);
  use_run_data(run_dir, config, data);
  return config;
}

}  // namespace goris
