#pragma once
// What a command writing beside a run must leave alone (core/io/output_path.h): the run's data set and
// the run's own inputs - config.json, point_cloud.ply, checkpoints/, log.csv and, unless the command is
// the one that writes it, the selection (selection.json and selection.npy).
#include <filesystem>

#include "core/io/output_path.h"
#include "train/config/train_config.h"

namespace goris {

OutputGuard run_output_guard(const std::filesystem::path& run_dir, const TrainConfig& config, bool keep_selection = true);

}  // namespace goris
