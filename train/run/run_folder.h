#pragma once
// A training run's folder (docs/design/architecture.md, The workflow and run folders): config.json (the
// TrainConfig, with the data set path so other commands find the data), checkpoints/, log.csv,
// point_cloud.ply (the final model in the standard 3DGS layout). Shared by `goris train | render | eval` and
// the editor.
#include <filesystem>
#include <string>

#include "core/scene/gaussians.h"
#include "train/config/train_config.h"

namespace goris {

std::filesystem::path run_config_path(const std::filesystem::path& run_dir);
std::filesystem::path run_ply_path(const std::filesystem::path& run_dir);

// Writes RUN/config.json through a temporary file.
void write_run_config(const std::filesystem::path& run_dir, const TrainConfig& config);
// Reads RUN/config.json; throws goris::Error naming the file when it is missing or invalid.
TrainConfig read_run_config(const std::filesystem::path& run_dir);

// Whether a run whose latest checkpoint is `checkpoint` wrote its outputs after it: point_cloud.ply (and an
// intrinsic run's environment.png) no older than the checkpoint. A run stopped between its last checkpoint
// and its outputs has reached its iterations but is not finished; resuming it writes them.
bool run_outputs_written_after(const std::filesystem::path& run_dir, const std::filesystem::path& checkpoint,
                               const TrainConfig& config);

// The trained model of a run on `device`: the latest checkpoint (which carries the 3D filter and the
// current SH degree), else point_cloud.ply. `source` receives the file used. Throws when the run has
// neither.
GaussianModel load_run_model(const std::filesystem::path& run_dir, Device device, std::string* source = nullptr);

}  // namespace goris
