#pragma once
// Where a run's data set is. A run folder names its data set in config.json ("data"); when the data set has
// moved since, the commands that read it (render, eval, select, remove, export, train --resume) are pointed
// at its new folder for one call (--data DIR), which must hold the same training views as the run was
// trained on: config.json records their fingerprint ("data_views").
#include <filesystem>
#include <string>

#include "core/io/dataset.h"
#include "train/config/train_config.h"

namespace goris {

// The training views' fingerprint: their count and an FNV-1a hash of each view's name and image size on
// disk, e.g. "40 views, 0123456789abcdef". Equal for copies of a data set, whatever their folder.
std::string training_views_fingerprint(const Dataset& dataset);

// Points `config` (a run's, read from RUN/config.json or a checkpoint) at its data set for one command.
// `data` empty: config.input.data must exist; when it does not, the error says that the path comes from
// RUN/config.json and how to point the run at the data set's new place (`how`, e.g. "--data DIR").
// `data` given: it must load and hold the training views the run records (config.input.data_views); a run
// that records none is taken on trust only when config.input.data no longer exists, with a warning.
// config.input.data becomes `data`, and a note on stderr says so. Throws goris::Error naming the folder and
// the problem.
void use_run_data(const std::filesystem::path& run_dir, TrainConfig& config, const std::string& data,
                  const std::string& how = "--data DIR");

// read_run_config (train/run/run_folder.h), then use_run_data: what render, eval, select, remove and
// export call with their --data option (empty when not given).
TrainConfig read_run_config_with_data(const std::filesystem::path& run_dir, const std::string& data);

}  // namespace goris
